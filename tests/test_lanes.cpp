// test_lanes.cpp: the packet stages (kernels/shared/lanes.h, MCL_PACKET_<stage> in the stage
// table). On the default OpenCL device, the conformance set rendered with every packet width
// W = 1, 4, 8, 16 is bit for bit the host backend's (film mean and M2, hi and lo parts); the sizes
// leave a partial last packet in some waves (10 x 10 pixels: 100 items per sample). And the W rule.
#include <doctest/doctest.h>

#include "cl/device_tuning.h"
#include "cl/devices.h"
#include "conformance/conformance.h"
#include "render/stage_bindings.h"
#include "render/stage_program.h"
#include "skip.h"
#include "util/errors.h"

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
  CHECK(stageRunsPackets(Stage::generate));
  CHECK(stageRunsPackets(Stage::shade_ao));
  CHECK(stageRunsPackets(Stage::accumulate));
  CHECK_FALSE(stageRunsPackets(Stage::intersect));
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
