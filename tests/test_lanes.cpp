// test_lanes.cpp: the packet stages (kernels/shared/lanes.h; every stage of the stage table but
// the fused ones). On the default OpenCL device, the conformance set rendered with every packet width
// W = 1, 4, 8, 16 is bit for bit the host backend's (film mean and M2, hi and lo parts); the sizes
// leave a partial last packet in some waves (10 x 10 pixels: 100 items per sample). Adaptive
// renders (active-pixel lists out of order; independent and sobol samplers) at W = 1, 4, 16 are byte
// for byte the host's. And the W rule.
#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <vector>

#include "cl/device_tuning.h"
#include "cli_runner.h"
#include "lanes_vs_host.h"
#include "cl/devices.h"
#include "conformance/conformance.h"
#include "render/stage_bindings.h"
#include "render/stage_program.h"
#include "skip.h"
#include "util/errors.h"

namespace test_file_lanes {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

TEST_CASE("packet stages: conformance set bit-identical to the host backend for W = 1, 4, 8, 16" *
          doctest::test_suite("opencl")) {
  for (unsigned lanes : {1u, 4u, 8u, 16u}) {
    CAPTURE(lanes);
    ConformanceOptions o;
    o.deviceSpecs = {""};
    o.lanes = lanes;
    o.set.size = 10;
    o.set.spp = 3;
    o.set.cornellSize = 12;
    o.set.cornellSpp = 2;
    o.set.cornellPath = sharedScenes() + "/cornell-box/scene.json";
    ConformanceReport report = runConformance(o);
    INFO(conformanceTable(report));
    REQUIRE(report.devices.size() == 1);
    REQUIRE(report.devices[0].buildOk);
    CHECK(report.devices[0].images.size() >= 7);
    for (const ImageComparison& c : report.devices[0].images) {
      CAPTURE(c.name);
      CHECK(c.rendered);
      CHECK(c.differingBits == 0);
      CHECK(c.maxAbsDiff == 0.0);
    }
    CHECK(report.pass);
  }
}

TEST_CASE("packet stages: W per device, --lanes values, and the stage table's packet stages" *
          doctest::test_suite("opencl")) {
  CHECK(resolveLanes(0, hostDeviceInfo()) == 1);
  CHECK(resolveLanes(16, hostDeviceInfo()) == 1);  // the host backend runs the scalar bodies
  CHECK_THROWS_AS(resolveLanes(3, hostDeviceInfo()), InputError);
  for (int s = 0; s < kStageCount; ++s) CHECK(stageRunsPackets(Stage(s)) == !stageIsFused(Stage(s)));
  CHECK(stageRunsPackets(Stage::shade_direct_hit));
  CHECK(stageRunsPackets(Stage::path_gather));
  CHECK(!stageRunsPackets(Stage::wave_path));
  CHECK(stageBuildOptions(BvhLayout::Wide, 1) == "");
  CHECK(stageBuildOptions(BvhLayout::Wide, 16) == "-DMCL_LANES=16");
  CHECK(stageBuildOptions(BvhLayout::Binary, 8) == "-DMCL_BVH_BINARY=1 -DMCL_LANES=8");
  const DeviceInfo d = selectDevice("");
  const DeviceTuning t = deviceTuning(d);
  CAPTURE(d.name);
  CAPTURE(d.version);
  if (d.isGpu) CHECK(t.lanes == 1);
  if (d.isCpu) CHECK((t.lanes == 4 || t.lanes == 8 || t.lanes == 16));
  if (d.isCpu && d.name.find("avx512") != std::string::npos) CHECK(t.lanes == 16);
  CHECK(resolveLanes(0, d) == t.lanes);
  CHECK(resolveLanes(4, d) == 4);
}

TEST_CASE("packet stages: adaptive sampling (active lists out of order, wrapping packets) matches the host backend" *
          doctest::test_suite("cli")) {
  const std::string scene = sharedScenes() + "/cornell-box/scene.json";
  MCL_SKIP_UNLESS(std::ifstream(scene).good(), "no shared Cornell box at " << scene);
  TempDir dir;
  // (integrator, sampler): the Sobol points' lane form, with packets that wrap the active list.
  const std::pair<const char*, const char*> configs[] = {
      {"ao", "independent"}, {"direct", "independent"}, {"direct", "sobol"}};
  for (const auto& row : configs) {
    const auto& integrator = std::get<0>(row);
    const auto& sampler = std::get<1>(row);
    CAPTURE(integrator);
    CAPTURE(sampler);
    const std::vector<std::string> common = {"render", scene, "-q", "--width", "37", "--height", "23",
                                             "--integrator", integrator, "--sampler", sampler,
                                             "--target-error", "0.05", "--min-spp", "4", "--max-spp", "32",
                                             "--overwrite"};
    checkLanesMatchHost(common, dir, {"1", "4", "16"});
  }
}

// The packet shade stages take every hit and every light: Lambertian hits in lanes, other kinds
// (glass, conductors) lane by lane, the light picked per lane (emitter triangles in lanes, the
// environment and the point/spot lights lane by lane). Scenes where those meet: the materials box
// (glass, metals, punctual lights beside the emitting quad, a constant environment) and the glossy
// scene under a sky map. Each image at W = 4 and 16 is byte for byte the host backend's.
TEST_CASE("packet stages: every kind and light kind in one scene matches the host backend" * doctest::test_suite("cli")) {
  TempDir dir;
  // The materials box with its rough glass as coated_diffuse (a rough coat over the box's white,
  // several walks per evaluation), its gold as a smooth coat over red and its mirror as a coated
  // rough gold (coated_conductor): the kinds it lacks. The
  // pixel filters' offsets in lanes: a tabulated filter (gaussian) there, the triangle on envgloss.
  const std::string box = std::string(MONTECL_SOURCE_DIR) + "/scenes/materials/";
  dir.write("coated.json", R"({"camera": {"position": [0, 1, 3.6], "target": [0, 0.9, 0], "fov_y": 38},
    "meshes": [{"file": ")" + box + R"(box.obj"}, {"file": ")" + box + R"(light.obj", "emission": [17, 12, 4]},
      {"file": ")" + box + R"(rough_glass.obj", "material": {"type": "coated_diffuse", "albedo": [0.8, 0.8, 0.8],
        "roughness": 0.3, "thickness": 0.05, "samples": 2}},
      {"file": ")" + box + R"(gold.obj", "material": {"type": "coated_diffuse", "albedo": [0.7, 0.1, 0.1], "ior": 1.6}},
      {"file": ")" + box + R"(mirror.obj", "material": {"type": "coated_conductor", "metal": "Au", "base_alpha": 0.1,
        "roughness": 0.2}}],
    "render": {"filter": {"type": "gaussian", "radius": 1.5, "sigma": 0.5}}})");
  for (const std::string name : {"materials", "envgloss", "coated"}) {
    const std::string scene = name == "coated" ? dir.file("coated.json")
                                               : std::string(MONTECL_SOURCE_DIR) + "/scenes/" + name + "/scene.json";
    for (const char* integrator : {"direct", "path"}) {
      CAPTURE(name);
      CAPTURE(integrator);
      std::vector<std::string> common = {"render", scene, "-q", "--width", "40", "--height", "28", "--spp", "4",
                                         "--integrator", integrator, "--overwrite"};
      if (name == "envgloss") common.insert(common.end(), {"--filter", "triangle,radius=1"});
      checkLanesMatchHost(common, dir, {"4", "16"});
    }
  }
}

}  // namespace test_file_lanes
