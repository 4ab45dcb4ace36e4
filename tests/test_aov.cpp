// test_aov.cpp: arbitrary output variables (first-hit albedo, normal, depth): their values on an
// analytic scene through the kernels, and `montecl render --aov` writing named EXR channels.
#include <doctest/doctest.h>

#include <cmath>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "render/wavefront.h"
#include "test_scenes.h"

using namespace montecl;
using namespace montecl_test;

namespace {

Film render(const Scene& s, const RenderOptions& o, RenderStats& stats) {
  static const DeviceInfo device = selectDevice("");
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(device, o);
  return r.render(s, bvh, stats);
}

}  // namespace

TEST_CASE("AOVs: first-hit albedo, facing normal and depth of a floor seen from above" * doctest::test_suite("opencl")) {
  Scene s = floorScene({0, 0, 0}, 2.0f, 40.0f, 16, 4);
  s.materials[0].albedo = {0.25f, 0.5f, 0.75f};
  RenderOptions o;
  o.aovs = true;
  RenderStats stats;
  Film f = render(s, o, stats);
  REQUIRE(f.aovSum.size() == 2 * f.mean.size());
  const float maxDepth = 2.0f / std::cos(glm::radians(20.0f * std::sqrt(2.0f)));
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    const float n = double(f.count[p]);
    REQUIRE(f.aovSum[2 * p].x / n == 0.25f);
    REQUIRE(f.aovSum[2 * p].y / n == 0.5f);
    REQUIRE(f.aovSum[2 * p].z / n == 0.75f);
    REQUIRE(f.aovSum[2 * p + 1].y / n == 1.0f);  // the normal faces the camera above
    const float depth = f.aovSum[2 * p].w / n;
    REQUIRE(depth >= 2.0f * (1.0f - 1e-5f));
    REQUIRE(depth <= maxDepth);
  }
  // Without AOVs the film has none, and the radiance is the same.
  RenderStats plain;
  Film g = render(s, {}, plain);
  CHECK(g.aovSum.empty());
  CHECK(g.mean == f.mean);
}

TEST_CASE("--aov all writes named albedo, normal and depth channels; --aov with .png is bad input" * doctest::test_suite("cli")) {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  CliResult r = runMontecl({"render", scene, "-o", dir.file("a.exr"), "--width", "16", "--height", "12", "--spp",
                            "2", "--aov", "all", "-q"});
  REQUIRE(r.exitCode == 0);
  LayeredImage img = readLayeredImage(dir.file("a.exr"));
  for (const char* name : {"R", "G", "B", "samples", "var.R", "var.G", "var.B", "albedo.R", "albedo.G", "albedo.B",
                           "N.X", "N.Y", "N.Z", "Z"}) {
    CAPTURE(name);
    CHECK(img.find(name) != nullptr);
  }
  CliResult bad = runMontecl({"render", scene, "-o", dir.file("a.png"), "--aov", "albedo", "-q"});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("--aov") != std::string::npos);
}
