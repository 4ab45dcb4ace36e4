// test_host_backend.cpp: the host backend (--device host) runs the kernels' stage functions on the
// CPU: selected without an OpenCL context, and bit-identical whatever the wave size or thread count.
#include <doctest/doctest.h>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include <cmath>

#include "render/frame_params.h"
#include "render/stage_runner.h"
#include "render/wavefront.h"
#include "util/errors.h"
#include "film_stats.h"
#include "nan_wave.h"
#include "test_scenes.h"

namespace test_file_host_backend {  // keeps this file's helpers apart in a unity batch

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

TEST_CASE("host backend: NaN camera rays are misses and every one is counted" * doctest::test_suite("cpu")) {
  // Without the fix there is no count (WaveCounts), and the traversal read an empty slot (SIGSEGV).
  std::unique_ptr<StageRunner> run = makeHostStageRunner();
  checkNanCameraWave(*run, floorScene({0, 0, 0}, 1.0f, 60.0f, 16, 1));
}

TEST_CASE("the renderer refuses a camera whose float basis is NaN, naming the key" * doctest::test_suite("cpu")) {
  // A camera set in code (not loaded, so not checked at load): without the check this rendered
  // NaN rays (and crashed in the wide traversal).
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 8, 1);
  s.path = "code.json";
  s.camera.up = glm::vec3(0.0f, 1e-30f, 0.0f);
  try {
    render(hostDeviceInfo(), s);
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("code.json: camera.up:") == 0);
  }
}

namespace {
// A corner (floor and two walls) with a block on the floor, all within [-0.9, 0.9] (offsetScale 1),
// scaled by k: positions, camera and ao_distance.
Scene cornerScene(float k) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<corner scene>";
  const float r = 0.9f * k, b = 0.2f * k;
  addQuad(s, {-r, 0, -r}, {-r, 0, r}, {r, 0, r}, {r, 0, -r});    // floor
  addQuad(s, {-r, 0, -r}, {-r, r, -r}, {-r, r, r}, {-r, 0, r});  // wall x = -r
  addQuad(s, {-r, 0, -r}, {r, 0, -r}, {r, r, -r}, {-r, r, -r});  // wall z = -r
  addQuad(s, {-b, 2 * b, -b}, {b, 2 * b, -b}, {b, 2 * b, b}, {-b, 2 * b, b});  // block top
  addQuad(s, {-b, 0, b}, {b, 0, b}, {b, 2 * b, b}, {-b, 2 * b, b});              // block front
  addQuad(s, {b, 0, -b}, {b, 2 * b, -b}, {b, 2 * b, b}, {b, 0, b});              // block side
  s.camera.position = glm::vec3(0.6f, 0.7f, 0.8f) * k;
  s.camera.target = glm::vec3(-0.2f, 0.1f, -0.2f) * k;
  s.camera.fovY = 60.0f;
  s.camera.width = s.camera.height = 24;
  s.render.spp = 16;
  s.render.aoDistance = 0.5f * k;
  s.render.aoSampling = montecl::AoSampling::Uniform;
  finishScene(s);
  return s;
}
}  // namespace

TEST_CASE("tiny scenes: a scene scaled by 2^-20 or 2^-40 renders the same AO bits, by 1e-6 or 1e-12 the same image within statistics" * doctest::test_suite("cpu")) {
  // Without scale-aware offsets the absolute 1/65536 offset throws AO rays of a 1e-6 scene far off
  // the surface (AO near 1 everywhere), and at 1e-12 cross(e1, e2) underflows: NaN normals.
  const DeviceInfo host = hostDeviceInfo();
  Film unit = render(host, cornerScene(1.0f));
  double unitSum = 0.0;
  for (const glm::vec4& m : unit.mean) unitSum += m.x;
  CHECK(unitSum > 0.2 * double(unit.mean.size()));
  CHECK(unitSum < 0.95 * double(unit.mean.size()));  // the corner and block occlude
  for (int e : {-20, -40}) {
    CAPTURE(e);
    Film f = render(host, cornerScene(std::ldexp(1.0f, e)));
    CHECK(f.mean == unit.mean);
    CHECK(f.m2 == unit.m2);
  }
  for (float k : {1e-6f, 1e-12f}) {
    CAPTURE(k);
    Film f = render(host, cornerScene(k));
    montecl_test::requireIndependentSamples(f);
    // Per pixel: the difference of two independent means, within 5 standard errors (or equal).
    int bad = 0;
    double sum = 0.0;
    for (std::size_t p = 0; p < f.mean.size(); ++p) {
      const double n = f.mean[p].w, d = double(f.mean[p].x) - unit.mean[p].x;
      const double se = std::sqrt((f.variance(p, 0) + unit.variance(p, 0)) / n);
      sum += f.mean[p].x;
      CHECK(std::isfinite(f.mean[p].x));
      bad += std::abs(d) > 5.0 * se + 1e-6;
    }
    CHECK(bad <= 2);
    CHECK(std::abs(sum - unitSum) < 0.02 * unitSum);
  }
}

}  // namespace test_file_host_backend
