// suggest.h: "did you mean" for a mistyped subcommand or option: the known name nearest to what was
// typed (edit distance). Reads the CLI11 app's subcommands and options and the command line only.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace montecl {

// The nearest of known to word within a few edits (at most 2, or a third of its length if more),
// else "".
std::string nearestName(const std::string& word, const std::vector<std::string>& known);

// A message for a command line that names an unknown subcommand or option, with the nearest known
// name: "unknown command 'rendr'; did you mean 'render'? (commands: ...)" or "unknown option
// '--integrater' of render; did you mean '--integrator'?". "" when every word is known (or none is
// close: CLI11's own message is then as good).
std::string unknownNameHint(CLI::App& app, int argc, char** argv);

}  // namespace montecl
