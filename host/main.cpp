// main.cpp: montecl's entry point: parses the command line and maps failures to exit codes.
#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>
#include <new>
#include <string>

#include "cl/cl_errors.h"
#include "cli/commands.h"
#include "cli/suggest.h"
#include "job/mpi.h"
#include "util/errors.h"
#include "util/heap_trim.h"

namespace {

// An error is one line: a library's message with newlines in it (CLI11's "Run with --help ..."
// line, a decoder's report) has them joined.
std::string oneLineError(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  for (std::size_t at = s.find('\n'); at != std::string::npos; at = s.find('\n', at)) s.replace(at, 1, "; ");
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace montecl;
  fixMmapThreshold();  // freed arrays leave the resident set (util/heap_trim.h)
  // Past a file-size limit (ulimit -f) a write would kill the process by SIGXFSZ, leaving a partial
  // temporary file; ignored, the write fails with EFBIG and the atomic writer reports it.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"montecl: Monte Carlo rendering with OpenCL"};
  app.set_version_flag("--version", MONTECL_VERSION);
  app.require_subcommand(1);
  int exitCode = kExitOk;
  addDevicesCommand(app, exitCode);
  addRenderCommand(app, exitCode);
  addIntegrateCommand(app, exitCode);
  addMergeCommand(app, exitCode);
  addBenchCommand(app, exitCode);
  addGenerateCommand(app, exitCode);
  addConformanceCommand(app, exitCode);
  addSettingsCommand(app, exitCode);
  addKindsCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A mistyped command or option gets the nearest known name instead of CLI11's listing.
    const std::string hint = unknownNameHint(app, argc, argv);
    std::cerr << "montecl: error: " << (hint.empty() ? oneLineError(e.what()) : hint) << " (see --help)\n";
    return jobs::failed(kExitBadInput);
  } catch (const InputError& e) {
    std::cerr << "montecl: error: " << oneLineError(e.what()) << "\n";
    return jobs::failed(kExitBadInput);  // under MPI: MPI_Abort, the whole job ends
  } catch (const cl::Error& e) {
    std::cerr << "montecl: error: " << describeClError(e) << "\n";
    return jobs::failed(kExitRuntime);
  } catch (const std::bad_alloc&) {
    std::cerr << "montecl: error: out of memory: the scene or image is too large for this machine\n";
    return jobs::failed(kExitRuntime);
  } catch (const std::exception& e) {
    std::cerr << "montecl: error: " << oneLineError(e.what()) << "\n";
    return jobs::failed(kExitRuntime);
  }
  return exitCode;
}
