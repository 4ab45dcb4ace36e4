// cmd_kinds.cpp: `montecl kinds [--markdown]`: the material and light kinds, read from their X-macro
// tables (kernels/shared/material_kinds.h, light_kinds.h), as text or as the markdown tables that
// docs/architecture.md holds (tests/check_docs.sh keeps the two equal).
#include <iostream>
#include <sstream>
#include <string>

#include "cli/commands.h"
#include "kernels/shared/light_kinds.h"
#include "kernels/shared/material_kinds.h"
#include "util/errors.h"

namespace montecl {
namespace {

std::string kindsMarkdown() {
  std::ostringstream out;
  out << "| material kind | tag | BSDF parameters | file |\n|---|---|---|---|\n";
#define MCL_KINDS_MATERIAL_ROW(kind, Params) \
  out << "| `" #kind "` | " << MCL_MATERIAL_##kind << " | `" #Params "` | `kernels/shared/bsdf_" #kind ".h` |\n";
  MCL_MATERIAL_KINDS(MCL_KINDS_MATERIAL_ROW)
#undef MCL_KINDS_MATERIAL_ROW
  out << "\n" << MCL_MATERIAL_KIND_COUNT << " material kinds; the first is the default (tag 0).\n\n";
  out << "| light kind | tag | file |\n|---|---|---|\n";
#define MCL_KINDS_LIGHT_ROW(kind) out << "| `" #kind "` | " << MCL_LIGHT_##kind << " | `kernels/shared/light_" #kind ".h` |\n";
  MCL_LIGHT_KINDS(MCL_KINDS_LIGHT_ROW)
#undef MCL_KINDS_LIGHT_ROW
  out << "\n" << MCL_LIGHT_KIND_COUNT << " light kinds, selected for next-event estimation in this order.\n";
  return out.str();
}

std::string kindsText() {
  std::ostringstream out;
  out << "material kinds (scene file \"type\"):";
#define MCL_KINDS_MATERIAL_NAME(kind, Params) out << " " #kind;
  MCL_MATERIAL_KINDS(MCL_KINDS_MATERIAL_NAME)
#undef MCL_KINDS_MATERIAL_NAME
  out << "\nlight kinds:";
#define MCL_KINDS_LIGHT_NAME(kind) out << " " #kind;
  MCL_LIGHT_KINDS(MCL_KINDS_LIGHT_NAME)
#undef MCL_KINDS_LIGHT_NAME
  out << "\n";
  return out.str();
}

}  // namespace

void addKindsCommand(CLI::App& app, int& exitCode) {
  CLI::App* cmd = app.add_subcommand("kinds", "List the material and light kinds");
  auto markdown = std::make_shared<bool>(false);
  cmd->add_flag("--markdown", *markdown, "Print the tables of docs/architecture.md");
  cmd->callback([markdown, &exitCode]() {
    std::cout << (*markdown ? kindsMarkdown() : kindsText());
    exitCode = kExitOk;
  });
}

}  // namespace montecl
