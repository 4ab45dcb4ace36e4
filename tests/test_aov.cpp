// test_aov.cpp: arbitrary output variables (first-hit albedo, normal, depth, emission seen
// directly): their values on an analytic scene and on the Cornell box's light through the kernels,
// and `montecl render --aov` writing named EXR channels.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "kernels/shared/camera.h"
#include "render/frame_params.h"
#include "render/wavefront.h"
#include "scene/scene.h"
#include "skip.h"
#include "test_scenes.h"

namespace test_file_aov {  // keeps this file's helpers apart in a unity batch

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
  REQUIRE(f.aovSum.size() == MCL_AOV_VECTORS * f.mean.size());
  const float maxDepth = 2.0f / std::cos(glm::radians(20.0f * std::sqrt(2.0f)));
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    const float n = double(f.count[p]);
    REQUIRE(f.aovSum[MCL_AOV_VECTORS * p].x / n == 0.25f);
    REQUIRE(f.aovSum[MCL_AOV_VECTORS * p].y / n == 0.5f);
    REQUIRE(f.aovSum[MCL_AOV_VECTORS * p].z / n == 0.75f);
    REQUIRE(f.aovSum[MCL_AOV_VECTORS * p + 1].y / n == 1.0f);  // the normal faces the camera above
    const float depth = f.aovSum[MCL_AOV_VECTORS * p].w / n;
    REQUIRE(depth >= 2.0f * (1.0f - 1e-5f));
    REQUIRE(depth <= maxDepth);
  }
  // Without AOVs the film has none, and the radiance is the same.
  RenderStats plain;
  Film g = render(s, {}, plain);
  CHECK(g.aovSum.empty());
  CHECK(g.mean == f.mean);
}

// Which pixels lie fully on the Cornell box's light (the quad x in [-0.24, 0.23], z in [-0.22,
// 0.16] at y = 1.98, nothing between it and the camera) is decided from the geometry alone: the
// camera rays through a pixel's four corners (camera.h, the renderer's own camera) all meet the
// quad strictly inside. A pixel none of whose neighbours' corners meets it sees none of it.
TEST_CASE("AOVs: the emission AOV is Le exactly on the Cornell box's pixels fully on the light, 0 away from it" *
          doctest::test_suite("cli shared-scenes")) {
  const std::string scene = sharedScenes() + "/cornell-box/scene.json";
  MCL_SKIP_UNLESS(std::ifstream(scene).good(), "no shared scenes at " << sharedScenes());
  const int w = 128, h = 128;
  for (const std::string integrator : {"direct", "path"}) {
    CAPTURE(integrator);
    TempDir dir;
    CliResult r = runMontecl({"render", scene, "--device", "host", "--width", "128", "--height", "128", "--spp", "2",
                              "--integrator", integrator, "--aov", "emission", "-o", dir.file("a.exr"), "-q"});
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    const LayeredImage img = readLayeredImage(dir.file("a.exr"));
    std::vector<std::string> warnings;
    Scene s = loadScene(scene, warnings);
    s.camera.width = w, s.camera.height = h;
    const FrameParams f = makeFrameParams(s.camera, s.render, 1u);
    std::vector<char> inside((w + 1) * (h + 1), 0);  // corner (x, y) of the pixel grid meets the light
    for (int y = 0; y <= h; ++y)
      for (int x = 0; x <= w; ++x) {
        const Ray ray = camera_ray(&f, float(x), float(y));
        const float t = (1.98f - ray.origin.y) / ray.dir.y;
        const float px = ray.origin.x + t * ray.dir.x, pz = ray.origin.z + t * ray.dir.z;
        inside[y * (w + 1) + x] = t > 0.0f && px > -0.24f + 1e-4f && px < 0.23f - 1e-4f && pz > -0.22f + 1e-4f &&
                                  pz < 0.16f - 1e-4f;
      }
    auto cornerIn = [&](int x, int y) {
      return x >= 0 && y >= 0 && x <= w && y <= h && inside[y * (w + 1) + x];
    };
    int full = 0, away = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(y) * w + x;
        const float e[3] = {(*img.find("emission.R"))[p], (*img.find("emission.G"))[p], (*img.find("emission.B"))[p]};
        if (cornerIn(x, y) && cornerIn(x + 1, y) && cornerIn(x, y + 1) && cornerIn(x + 1, y + 1)) {
          ++full;
          CAPTURE(p);
          CHECK(e[0] == 17.0f);
          CHECK(e[1] == 12.0f);
          CHECK(e[2] == 4.0f);
          CHECK((*img.find("R"))[p] >= 17.0f);  // the estimate holds Le plus light reflected by the light
          continue;
        }
        bool near = false;
        for (int dy = -1; dy <= 2; ++dy)
          for (int dx = -1; dx <= 2; ++dx) near = near || cornerIn(x + dx, y + dy);
        if (near) continue;
        ++away;
        CAPTURE(p);
        CHECK(e[0] == 0.0f);
        CHECK(e[1] == 0.0f);
        CHECK(e[2] == 0.0f);
      }
    MESSAGE(integrator << ": " << full << " pixels fully on the light, " << away << " away from it");
    CHECK(full >= 20);
    CHECK(away > w * h * 9 / 10);
  }
}

TEST_CASE("--aov all writes named albedo, normal and depth channels; --aov with .png is bad input" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  CliResult r = runMontecl({"render", scene, "-o", dir.file("a.exr"), "--width", "16", "--height", "12", "--spp",
                            "2", "--aov", "all", "-q"});
  REQUIRE(r.exitCode == 0);
  LayeredImage img = readLayeredImage(dir.file("a.exr"));
  for (const char* name : {"R", "G", "B", "samples", "var.R", "var.G", "var.B", "albedo.R", "albedo.G", "albedo.B",
                           "N.X", "N.Y", "N.Z", "Z", "emission.R", "emission.G", "emission.B"}) {
    CAPTURE(name);
    CHECK(img.find(name) != nullptr);
  }
  CliResult bad = runMontecl({"render", scene, "-o", dir.file("a.png"), "--aov", "albedo", "-q"});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("--aov") != std::string::npos);
}

// The sub-sequence error estimate costs only the renders that use it: a default sobol EXR has no
// err.* or split layers (one sequence per pixel), --error-estimate and --target-error write them.
TEST_CASE("sobol EXR: err.* and split layers only with --error-estimate or --target-error" * doctest::test_suite("cli")) {
  TempDir dir;
  const std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  auto layers = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render", scene, "-o", dir.file("e.exr"), "--width", "8", "--height", "6",
                                     "--spp", "4", "--overwrite", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = runMontecl(args);
    REQUIRE(r.exitCode == 0);
    const LayeredImage img = readLayeredImage(dir.file("e.exr"));
    return std::pair<bool, bool>{img.find("err.R") != nullptr, img.find("split3.R") != nullptr};
  };
  const std::pair<bool, bool> plain = layers({}), asked = layers({"--error-estimate"}),
                              adaptive = layers({"--target-error", "0.5", "--min-spp", "4", "--max-spp", "8"});
  CHECK_FALSE(plain.first);
  CHECK_FALSE(plain.second);
  CHECK(asked.first);
  CHECK(asked.second);
  CHECK(adaptive.first);
  CHECK(adaptive.second);
}

}  // namespace test_file_aov
