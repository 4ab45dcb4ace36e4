// test_profile.cpp: `montecl render --profile` through the real command line: the table names
// every stage the integrator launches (and only those), each launched once per wave, with a
// positive time; the stage shares plus the "host (device idle)" row sum to 100% (to the printed
// rounding) and the host row is not negative (stage times never exceed the render's wall time).
// On an OpenCL device (profiling events) and on the host backend (host timers).
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace test_file_profile {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {

struct Row {
  double ms = 0.0, share = 0.0;
  long launches = -1;  // -1: the row has no launch count (host, total)
};

// The rows of the profile table in montecl's stdout, by name.
std::map<std::string, Row> parseProfile(const std::string& out) {
  std::map<std::string, Row> rows;
  std::istringstream in(out);
  std::string line;
  bool inTable = false;
  while (std::getline(in, line)) {
    if (line.rfind("profile:", 0) == 0) {
      inTable = true;
      std::getline(in, line);  // the header
      continue;
    }
    if (!inTable || line.size() < 2 || line[0] != ' ' || line.find('%') == std::string::npos) continue;
    // "  name (may have spaces)   ms  share%  [launches]": the name is everything before the first
    // number column, found from the right.
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string t; words >> t;) w.push_back(t);
    std::size_t pct = 0;
    while (pct < w.size() && w[pct].back() != '%') pct++;
    REQUIRE(pct >= 2);
    REQUIRE(pct < w.size());
    std::string name;
    for (std::size_t i = 0; i + 1 < pct; ++i) name += (i ? " " : "") + w[i];
    Row r;
    r.ms = std::stod(w[pct - 1]);
    r.share = std::stod(w[pct].substr(0, w[pct].size() - 1));
    if (pct + 1 < w.size()) r.launches = std::stol(w[pct + 1]);
    rows[name] = r;
  }
  return rows;
}

void checkProfile(const CliResult& r, const std::vector<std::string>& stages, long waves) {
  INFO(r.out << r.err);
  REQUIRE(r.exitCode == 0);
  std::map<std::string, Row> rows = parseProfile(r.out);
  REQUIRE(rows.count("total") == 1);
  REQUIRE(rows.count("host (device idle)") == 1);
  CHECK(rows.size() == stages.size() + 2);  // no stage that was not launched
  double sum = 0.0, stageMs = 0.0;
  for (const std::string& s : stages) {
    INFO("stage " << s);
    REQUIRE(rows.count(s) == 1);
    CHECK(rows[s].launches == waves);
    CHECK(rows[s].ms >= 0.0);
    stageMs += rows[s].ms;
    sum += rows[s].share;
  }
  const Row& host = rows["host (device idle)"];
  CHECK(stageMs > 0.0);
  CHECK(host.ms >= 0.0);
  sum += host.share;
  CHECK(rows["total"].share == doctest::Approx(100.0));
  CHECK(std::fabs(sum - 100.0) <= 0.05 * double(stages.size() + 1) + 1e-9);  // each share rounded to 0.1%
}

}  // namespace

TEST_CASE("render --profile on OpenCL: every direct stage with AOVs, once per wave, shares sum to 100%" *
          doctest::test_suite("cli")) {
  TempDir dir;
  // 24x16 pixels x 8 spp = 3072 samples in waves of 1024: 3 waves (stage by stage: --no-fuse).
  CliResult r = runMontecl({"render", montecl_test::demoScene(), "--width", "24", "--height", "16", "--spp", "8",
                            "--integrator", "direct", "--aov", "all", "--wave-size", "1024", "--profile", "-q",
                            "--no-fuse", "-o", dir.file("p.exr")});
  checkProfile(r, {"generate", "intersect", "shade_direct", "intersect (bounce rays)", "shade_direct_hit",
                   "intersect_shadow", "accumulate", "record_aov", "accumulate_aov"},
               3);
}

TEST_CASE("render --profile on the host backend: the AO stages, shares sum to 100%" * doctest::test_suite("cli")) {
  TempDir dir;
  CliResult r = runMontecl({"render", montecl_test::demoScene(), "--width", "24", "--height", "16", "--spp", "4",
                            "--integrator", "ao", "--device", "host", "--wave-size", "768", "--profile", "-q", "-o",
                            dir.file("p.png")});
  checkProfile(r, {"generate", "intersect", "shade_ao", "intersect_shadow", "accumulate"}, 2);
}

TEST_CASE("render without --profile prints no profile" * doctest::test_suite("cli")) {
  TempDir dir;
  CliResult r = runMontecl({"render", montecl_test::demoScene(), "--width", "8", "--height", "8", "--spp", "1", "-q",
                            "-o", dir.file("p.png")});
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("profile:") == std::string::npos);
}

}  // namespace test_file_profile

namespace test_file_profile {

// The "shading: P% of N hits in lane types" line's P and N; N = -1 when absent.
std::pair<double, long> laneTally(const std::string& out) {
  const std::size_t at = out.find("\nshading: ");
  if (at == std::string::npos) return {0.0, -1};
  std::istringstream in(out.substr(at + 10));
  double pct = 0.0;
  std::string percent, of;
  long hits = -1;
  in >> pct >> percent >> of >> hits;
  return {pct, hits};
}

// The tally counts hits, not work items: the host backend (one lane) and the OpenCL device (W
// lanes, fused stages) count the same hits the same way; a scene of flat diffuse walls is shaded
// wholly in lane types, the materials box (glass, metals) too by both integrators, the box with a
// coated_conductor sphere and glass, and the same box with the sphere placed as two instances.
TEST_CASE("render --profile: the shading lane tally is the hits' own (host backend = OpenCL), 100% for diffuse walls" *
          doctest::test_suite("cli")) {
  TempDir dir;
  const std::string src = std::string(MONTECL_SOURCE_DIR) + "/scenes/materials/";
  dir.write("coated.json", R"({"camera": {"position": [0, 1, 3.6], "target": [0, 0.9, 0], "fov_y": 38},
    "meshes": [{"file": ")" + src + R"(box.obj"}, {"file": ")" + src + R"(light.obj", "emission": [17, 12, 4]},
               {"file": ")" + src + R"(gold.obj", "material": {"type": "coated_conductor", "metal": "Au"}},
               {"file": ")" + src + R"(glass.obj", "material": {"type": "dielectric", "ior": 1.5}}]})");
  dir.write("placed.json", R"({"camera": {"position": [0, 1, 3.6], "target": [0, 0.9, 0], "fov_y": 38},
    "meshes": [{"file": ")" + src + R"(box.obj"}, {"file": ")" + src + R"(light.obj", "emission": [17, 12, 4]},
               {"file": ")" + src + R"(gold.obj", "material": {"type": "coated_conductor", "metal": "Au"},
                "instances": [{"translate": [0, 0, 0]}, {"translate": [0.3, 0, 0.2]}]}]})");
  for (const std::string& scene : {src + "scene.json", dir.file("coated.json"), dir.file("placed.json")}) {
    for (const char* integrator : {"path", "direct"}) {
      CAPTURE(scene);
      CAPTURE(integrator);
      std::pair<double, long> tallies[2];
      int k = 0;
      for (const char* device : {"host", "default"}) {
        CAPTURE(device);
        std::vector<std::string> args = {"render", scene, "--width", "24", "--height", "16", "--spp", "2",
                                         "--integrator", integrator, "--max-depth", "4", "--profile", "-q", "-o",
                                         dir.file("m.pfm"), "--overwrite"};
        if (std::string(device) == "host") args.insert(args.end(), {"--device", "host"});
        CliResult r = runMontecl(args);
        INFO(r.out << r.err);
        REQUIRE(r.exitCode == 0);
        tallies[k] = laneTally(r.out);
        CHECK(tallies[k].second > 24 * 16);  // most camera rays hit
        CHECK(tallies[k].first == 100.0);  // every material kind, instanced or not, in lane types
        ++k;
      }
      CHECK(tallies[0].second == tallies[1].second);
      CHECK(tallies[0].first == tallies[1].first);
    }
  }
  // Flat diffuse walls only: every hit in lane types; direct: one shading hit per camera ray that hits.
  dir.write("walls.json", R"({"camera": {"position": [0, 1, 3.6], "target": [0, 0.9, 0], "fov_y": 38},
    "meshes": [{"file": ")" + std::string(MONTECL_SOURCE_DIR) + R"(/scenes/materials/box.obj"},
               {"file": ")" + std::string(MONTECL_SOURCE_DIR) + R"(/scenes/materials/light.obj", "emission": [17, 12, 4]}]})");
  CliResult r = runMontecl({"render", dir.file("walls.json"), "--width", "24", "--height", "16", "--spp", "2",
                            "--integrator", "direct", "--profile", "-q", "-o", dir.file("w.pfm"), "--overwrite"});
  INFO(r.out << r.err);
  REQUIRE(r.exitCode == 0);
  const std::pair<double, long> walls = laneTally(r.out);
  CHECK(walls.first == 100.0);
  CHECK(walls.second > 0);
  CHECK(walls.second <= 24 * 16 * 2);
  // Without --profile nothing is counted or printed.
  CliResult quiet = runMontecl({"render", dir.file("walls.json"), "--width", "8", "--height", "8", "--spp", "1", "-q",
                                "-o", dir.file("q.pfm"), "--overwrite"});
  CHECK(laneTally(quiet.out).second == -1);
}

}  // namespace test_file_profile
