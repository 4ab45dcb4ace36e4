// test_convergence_metrics.cpp: runs scripts/image_metrics_test.py (the relMSE, dropped-top-0.1% and
// FLIP helpers of scripts/convergence.py --vs-time, against hand-computed values) in Mitsuba's venv,
// which has numpy and flip_evaluator; skipped when that venv or its FLIP is absent.
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "cli_runner.h"
#include "skip.h"

namespace test_file_convergence_metrics {  // keeps this file's helpers apart in a unity batch

std::string venvPython() {
  if (const char* v = std::getenv("MONTECL_MITSUBA_VENV")) return std::string(v) + "/bin/python";
  const char* home = std::getenv("HOME");
  return std::string(home ? home : "") + "/.cache/montecl/mitsuba-venv/bin/python";
}

TEST_CASE("image_metrics: relMSE, its dropped top 0.1% and FLIP's LDR images match hand-computed values" *
          doctest::test_suite("cli")) {
  MCL_SKIP_UNLESS(std::ifstream(venvPython()).good(),
                  "no Mitsuba venv at " << venvPython() << " (run scripts/setup.sh --mitsuba)");
  const montecl_test::CliResult r =
      montecl_test::runProgram({venvPython(), MONTECL_SOURCE_DIR "/scripts/image_metrics_test.py"});
  MCL_SKIP_UNLESS(r.exitCode != 77, "flip_evaluator or numpy missing: " << r.out);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("PASS") != std::string::npos);
}

}  // namespace test_file_convergence_metrics
