// test_fused_waves.cpp: the fused wave stages (kernels/stages/wave_fused.h) through the real command
// line on the default OpenCL device. AO, direct and path renders are byte for byte the same fused,
// unfused (--no-fuse) and on the host backend, for packet widths 16 and 4, with planned waves,
// fixed waves that cut the sample blocks or hold a pixel twice (where the wave loop must fall back
// to a launch per stage), adaptive sampling and both samplers. And --profile shows which launches
// ran: one fused launch per wave (AO, direct) or per bounce (path, plus accumulate), and the stage
// launches with AOVs, --no-fuse or one lane.
#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"
#include "skip.h"

namespace test_file_fused_waves {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// The stage names of a --profile table in montecl's stdout (the rows before the host row).
std::vector<std::string> profiledStages(const std::string& out) {
  std::vector<std::string> names;
  const std::size_t table = out.find("profile:");
  if (table == std::string::npos) return names;
  std::size_t at = out.find('\n', out.find('\n', table) + 1);  // past the title and the header
  while (at != std::string::npos && at + 1 < out.size()) {
    const std::size_t end = out.find('\n', at + 1);
    const std::string line = out.substr(at + 1, end - at - 1);
    at = end;
    if (line.rfind("  host", 0) == 0 || line.rfind("  total", 0) == 0) break;
    const std::size_t name = line.find_first_not_of(' ');
    if (name == std::string::npos) break;
    names.push_back(line.substr(name, line.find("  ", name) - name));
  }
  return names;
}

}  // namespace

TEST_CASE("fused waves: AO, direct and path are byte-identical fused, unfused and on the host backend" *
          doctest::test_suite("cli")) {
  const std::string scene = sharedScenes() + "/cornell-box/scene.json";
  MCL_SKIP_UNLESS(std::ifstream(scene).good(), "no shared Cornell box at " << scene);
  TempDir dir;
  // (integrator, spp, extra options): planned waves (C = 16 at W = 16); waves of 992 items that
  // cut the 16-sample blocks; waves of 4000 items, over the 247 pixels' single runs (a pixel
  // twice in one wave: the stages' launches); adaptive rounds; sobol; every AOV (an EXR, whose
  // bytes carry no device or time, so it is compared whole).
  const std::vector<std::vector<std::string>> configs = {
      {"ao", "16"},
      {"direct", "16"},
      {"path", "16"},
      {"direct", "32", "--wave-size", "992"},
      {"direct", "32", "--wave-size", "4000"},
      {"ao", "32", "--wave-size", "4000"},
      {"path", "24", "--wave-size", "1000"},
      {"direct", "16", "--target-error", "0.05", "--min-spp", "4", "--max-spp", "32"},
      {"direct", "16", "--sampler", "sobol"},
      {"path", "16", "--sampler", "sobol"},
      {"ao", "16", "--aov", "all"},
      {"direct", "16", "--aov", "all"},
      {"path", "16", "--aov", "all"}};
  for (const std::vector<std::string>& c : configs) {
    std::string label;
    for (const std::string& w : c) label += w + " ";
    CAPTURE(label);
    const std::string ext = label.find("--aov") != std::string::npos ? ".exr" : ".pfm";
    std::vector<std::string> common = {"render", scene, "-q", "--width", "19", "--height", "13",
                                       "--integrator", c[0], "--spp", c[1], "--overwrite"};
    common.insert(common.end(), c.begin() + 2, c.end());
    checkLanesMatchHostCli(common, dir, ext);
  }
}

TEST_CASE("fused waves: --profile shows one fused launch per wave or bounce, and the stages where not fused" *
          doctest::test_suite("cli")) {
  TempDir dir;
  auto stages = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render", demoScene(), "--width", "24", "--height", "16", "--spp", "16",
                                     "--profile", "-q", "--overwrite", "-o", dir.file("p.exr")};
    args.insert(args.end(), extra.begin(), extra.end());
    CliResult r = runMontecl(args);
    INFO(r.out << r.err);
    REQUIRE(r.exitCode == 0);
    return profiledStages(r.out);
  };
  using V = std::vector<std::string>;
  CHECK(stages({"--integrator", "ao", "--lanes", "16"}) == V{"wave_ao"});
  CHECK(stages({"--integrator", "direct", "--lanes", "16"}) == V{"wave_direct"});
  CHECK(stages({"--integrator", "path", "--lanes", "16"}) == V{"wave_path", "accumulate"});
  // AOVs are recorded and summed inside the fused stage (path: summed with accumulate, per wave).
  CHECK(stages({"--integrator", "direct", "--lanes", "16", "--aov", "albedo"}) == V{"wave_direct"});
  CHECK(stages({"--integrator", "path", "--lanes", "16", "--aov", "albedo"}) ==
        V{"wave_path", "accumulate", "accumulate_aov"});
  // --no-fuse and one lane (GPUs' width) launch the stages one by one.
  CHECK(stages({"--integrator", "direct", "--lanes", "16", "--no-fuse"}) ==
        V{"generate", "intersect", "shade_direct", "intersect (bounce rays)", "shade_direct_hit", "intersect_shadow",
          "accumulate"});
  CHECK(stages({"--integrator", "path", "--lanes", "1"}) ==
        V{"generate", "intersect", "shade_path", "intersect_shadow", "path_gather", "accumulate"});
}

}  // namespace test_file_fused_waves
