// test_vs_mitsuba.cpp: the independent-renderer check, scripts/vs_mitsuba.py, through the real
// command line: montecl and Mitsuba 3 render the shared Cornell box and must agree per pixel
// (|z| > 4 on <= 0.1% of pixel channels, |mean z| <= 0.1; the script prints PASS/FAIL and exits
// 1 on FAIL). Skipped unless Mitsuba's venv exists (`scripts/setup.sh --mitsuba`; CI does not
// install it by default) and the shared scenes are present. The path-integrator cases also skip
// while montecl has no `--integrator path`.
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "skip.h"

using montecl_test::CliResult;
using montecl_test::runMontecl;
using montecl_test::runProgram;
using montecl_test::sharedScenes;

namespace {

std::string mitsubaVenvPython() {
  if (const char* v = std::getenv("MONTECL_MITSUBA_VENV")) return std::string(v) + "/bin/python";
  const char* home = std::getenv("HOME");
  return std::string(home ? home : "") + "/.cache/montecl/mitsuba-venv/bin/python";
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

CliResult runVsMitsuba(const std::vector<std::string>& extra) {
  std::vector<std::string> argv = {mitsubaVenvPython(), MONTECL_SOURCE_DIR "/scripts/vs_mitsuba.py",
                                   sharedScenes() + "/cornell-box/scene.json", "--montecl", MONTECL_EXE,
                                   "--width", "64", "--height", "64", "--no-timing"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return runProgram(argv);
}

// montecl renders with --integrator path (exit 0), or refuses the choice (exit 2: not landed).
bool monteclHasPath() {
  montecl_test::TempDir dir;
  return runMontecl({"render", MONTECL_SOURCE_DIR "/scenes/demo/scene.json", "--integrator", "path", "--spp", "1",
                     "--width", "2", "--height", "2", "-q", "-o", dir.file("p.png")})
             .exitCode == 0;
}

}  // namespace

#define MCL_SKIP_UNLESS_MITSUBA()                                                                          \
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()),                                                             \
                  "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");    \
  MCL_SKIP_UNLESS(exists(sharedScenes() + "/cornell-box/scene.json"), "no shared scenes at " << sharedScenes())

TEST_CASE("vs_mitsuba: Cornell box, direct MIS, agrees with Mitsuba 3 per pixel" *
          doctest::test_suite("cli shared-scenes slow")) {
  MCL_SKIP_UNLESS_MITSUBA();
  CliResult r = runVsMitsuba({"--spp", "256", "--integrator", "direct", "--direct-sampling", "mis"});
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("PASS") != std::string::npos);
}

TEST_CASE("vs_mitsuba: Cornell box, path at max depth 3 and unlimited, agrees with Mitsuba 3 per pixel" *
          doctest::test_suite("cli shared-scenes slow")) {
  MCL_SKIP_UNLESS_MITSUBA();
  MCL_SKIP_UNLESS(monteclHasPath(), "montecl has no --integrator path yet");
  for (const char* depth : {"3", "-1"}) {
    INFO("max depth " << depth);
    CliResult r = runVsMitsuba({"--spp", "256", "--integrator", "path", "--max-depth", depth, "--rr-depth", "5"});
    INFO(r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("PASS") != std::string::npos);
  }
}

TEST_CASE("vs_mitsuba: FAIL (exit 1) when montecl's red wall has albedo 0.5 instead of 0.63" *
          doctest::test_suite("cli shared-scenes slow")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  const std::string box = sharedScenes() + "/cornell-box/";
  std::string mtl = montecl_test::readAll(box + "CornellBox-Original.mtl");
  const std::string red = "Kd 0.63 0.065 0.05";
  REQUIRE(mtl.find(red) != std::string::npos);
  mtl.replace(mtl.find(red), red.size(), "Kd 0.5 0.065 0.05");
  dir.write("CornellBox-Original.mtl", mtl);
  dir.write("CornellBox-Original.obj", montecl_test::readAll(box + "CornellBox-Original.obj"));
  dir.write("scene.json", montecl_test::readAll(box + "scene.json"));
  CliResult r = runVsMitsuba({"--spp", "64", "--width", "32", "--height", "32", "--integrator", "direct",
                              "--montecl-scene", dir.file("scene.json")});
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}
