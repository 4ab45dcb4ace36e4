// cli_runner.h: runs the real montecl executable in a subprocess for end-to-end tests.
#pragma once
#include <string>
#include <vector>

namespace montecl_test {

struct CliResult {
  int exitCode = -1;  // exit status, or 128 + signal number when killed by a signal
  std::string out, err;
};

// Runs MONTECL_EXE with args (no shell), capturing stdout and stderr. extraEnv: "NAME=value"
// entries added to (or replacing those in) the child's environment.
CliResult runMontecl(const std::vector<std::string>& args, const std::vector<std::string>& extraEnv = {});

// Runs argv[0] (searched in PATH) with the rest of argv, like runMontecl.
CliResult runProgram(const std::vector<std::string>& argv, const std::vector<std::string>& extraEnv = {});

// The non-empty lines of a text file (expect.txt of the bad-input cases).
std::vector<std::string> readLines(const std::string& path);

// A fresh empty temporary folder for one test, removed by the destructor.
struct TempDir {
  TempDir();
  ~TempDir();
  std::string path;
  std::string file(const std::string& name) const { return path + "/" + name; }
  void write(const std::string& name, const std::string& text) const;
};

}  // namespace montecl_test
