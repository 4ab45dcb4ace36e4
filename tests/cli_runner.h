// cli_runner.h: runs the real montecl executable in a subprocess for end-to-end tests.
#pragma once
#include <string>
#include <vector>

namespace montecl_test {

struct CliResult {
  int exitCode = -1;  // exit status, or 128 + signal number when killed by a signal
  std::string out, err;
};

// Runs MONTECL_EXE with args (no shell), capturing stdout and stderr.
CliResult runMontecl(const std::vector<std::string>& args);

// A fresh empty temporary folder for one test, removed by the destructor.
struct TempDir {
  TempDir();
  ~TempDir();
  std::string path;
  std::string file(const std::string& name) const { return path + "/" + name; }
  void write(const std::string& name, const std::string& text) const;
};

}  // namespace montecl_test
