// test_host_backend.cpp: the host backend (--device host) runs the kernels' stage functions on the
// CPU: selected without an OpenCL context, and bit-identical whatever the wave size or thread count.
#include <doctest/doctest.h>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "render/wavefront.h"
#include "test_scenes.h"

using namespace montecl;
using namespace montecl_test;

namespace {

Film render(const DeviceInfo& device, const Scene& scene, RenderOptions options = {}) {
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, options);
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

}  // namespace

TEST_CASE("host backend: selected by --device host, needs no OpenCL context" * doctest::test_suite("cpu")) {
  DeviceInfo host = selectDevice("host");
  REQUIRE(host.isHost);
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 8, 4);
  s.render.aoSampling = montecl::AoSampling::Cosine;
  Film f = render(host, s);
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    REQUIRE(double(f.count[p]) == 4.0f);
    REQUIRE(f.mean[p].x == 1.0f);
  }
}

TEST_CASE("host backend: bit-identical across wave sizes (one thread or several)" * doctest::test_suite("cpu")) {
  const DeviceInfo host = hostDeviceInfo();
  Scene s = wallScene(48, 4);  // 9216 items: the default wave runs on several threads
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.seed = 3;
  Film reference = render(host, s);
  for (std::uint64_t wave : {1000ull, 4096ull + 17}) {
    RenderOptions o;
    o.waveSize = wave;
    CAPTURE(wave);
    Film f = render(host, s, o);
    CHECK(f.mean == reference.mean);
    CHECK(f.m2 == reference.m2);
  }
}

TEST_CASE("adaptive sampling with minSpp above maxSpp is an error, not a clamp" * doctest::test_suite("cpu")) {
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 4, 4);
  RenderOptions o;
  o.targetError = 0.05;
  o.minSpp = 64;
  o.maxSpp = 8;
  CHECK_THROWS_AS(render(hostDeviceInfo(), s, o), std::invalid_argument);
  o.maxSpp = 64;  // equal is fine
  Film f = render(hostDeviceInfo(), s, o);
  CHECK(double(f.count[0]) == 64.0f);
}
