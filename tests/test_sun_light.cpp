// test_sun_light.cpp: the sun light (kernels/shared/light_sun.h, a distant disk sampled uniformly
// by solid angle) through the real kernels on a diffuse floor (albedo rho): a disk of angular
// radius alpha fully above the horizon, at theta from the zenith, gives exactly rho/pi E cos(theta)
// (the cone's mean direction is its axis: z-test of the image mean); a half-plane occluder right
// above the lit point hides exactly half the disk (rho/pi E / 2, z-test), where a directional
// light is all or nothing; BSDF-only sampling never reaches it; bad "sun" input is one line.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "render/wavefront.h"
#include "scene/builtin_scenes.h"
#include "util/errors.h"

namespace test_file_sun_light {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
const glm::vec3 kRho(0.5f, 0.6f, 0.7f);
const glm::vec3 kE(0.7f, 0.4f, 0.2f);

// A 4 x 4 floor y = 0 seen straight down from 0.05 above `at` (every pixel sees `at` to 1e-5),
// optionally under the occluder y = 1, x < 0.
Scene floorUnder(glm::vec3 at, const LightDesc& light, bool occluder, int spp) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<floor under the sun>";
  s.materials = {MaterialDesc{"floor", kRho, glm::vec3(0.0f)}};
  addQuad(s, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, 0);
  if (occluder) addQuad(s, {-3, 1, 3}, {0, 1, 3}, {0, 1, -3}, {-3, 1, -3}, 0);
  s.camera.position = at + glm::vec3(0, 0.05f, 0);
  s.camera.target = at;
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 0.01f;
  s.camera.width = s.camera.height = 4;
  s.render.spp = spp;
  s.render.integrator = Integrator::Direct;
  s.lights = {light};
  finishScene(s);
  return s;
}

Film render(Scene s, DirectSampling strategy = DirectSampling::Light) {
  static const DeviceInfo device = selectDevice("");
  s.render.directSampling = strategy;
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(s, bvh, stats);
}

LightDesc sun(double thetaDeg, float angleDeg, PunctualKind kind = PunctualKind::Sun) {
  const double a = thetaDeg * kPi / 180.0;
  LightDesc l;
  l.kind = kind;
  l.direction = glm::vec3(float(std::sin(a)), float(-std::cos(a)), 0.0f);
  l.color = kE;
  l.angleDegrees = angleDeg;
  return l;
}

double zOf(const Film& f, int c, double expected) {
  const ImageEstimate e = imageEstimate(f, c);
  const double se = std::max(e.standardError, 1e-7 * expected);
  MESSAGE("channel " << c << ": " << e.mean << " +- " << e.standardError << ", expected " << expected);
  return (e.mean - expected) / se;
}

}  // namespace

TEST_CASE("sun light: a disk above the horizon gives rho/pi E cos(theta) exactly (z-test)" *
          doctest::test_suite("opencl")) {
  for (double deg : {0.0, 40.0, 75.0}) {
    for (float angle : {0.53f, 20.0f}) {  // 75 + 10 degrees: still above the horizon
      CAPTURE(deg);
      CAPTURE(angle);
      const Film f = render(floorUnder({0.2f, 0, -0.1f}, sun(deg, angle), false, 64));
      for (int c = 0; c < 3; ++c)
        CHECK(std::fabs(zOf(f, c, double(kRho[c]) / kPi * double(kE[c]) * std::cos(deg * kPi / 180.0))) < 4.0);
    }
  }
  // No BSDF ray reaches it (next-event estimation only, documented).
  const Film brdf = render(floorUnder({0.2f, 0, -0.1f}, sun(0.0, 5.0f), false, 4), DirectSampling::Brdf);
  CHECK(imageMean(brdf, 1) == 0.0);
}

TEST_CASE("sun light: a half-plane occluder above the point hides half the disk; a directional light is all or nothing" *
          doctest::test_suite("opencl")) {
  // Straight down, angular diameter 10 degrees, the occluder's edge right above x = 0: by symmetry
  // half the disk (and half its cosine-weighted irradiance) is hidden.
  const Film half = render(floorUnder({0.0f, 0, 0.3f}, sun(0.0, 10.0f), true, 256));
  for (int c = 0; c < 3; ++c) CHECK(std::fabs(zOf(half, c, double(kRho[c]) / kPi * double(kE[c]) * 0.5)) < 4.0);
  // 0.04 under the occluder (tan 5 degrees = 0.0875): a penumbra, strictly between 0 and fully lit;
  // the directional light there is fully shadowed.
  const Film pen = render(floorUnder({-0.04f, 0, 0.3f}, sun(0.0, 10.0f), true, 64));
  const double full = double(kRho[1]) / kPi * double(kE[1]);
  CHECK(imageMean(pen, 1) > 0.05 * full);
  CHECK(imageMean(pen, 1) < 0.45 * full);
  const Film dir = render(floorUnder({-0.04f, 0, 0.3f}, sun(0.0, 10.0f, PunctualKind::Directional), true, 4));
  CHECK(imageMean(dir, 1) == 0.0);
}

TEST_CASE("sun light: bad input is one line naming the key" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto load = [&](const std::string& light) {
    dir.write("s.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 40, "width": 8, "height": 8}, "meshes": [{"file": "m.obj"}], "lights": [)" +
                            light + "]}");
    std::vector<std::string> warnings;
    return loadScene(dir.file("s.json"), warnings);
  };
  const Scene ok = load(R"({"type": "sun", "direction": [0, -1, 0], "irradiance": [1, 1, 1], "angle": 2})");
  REQUIRE(ok.lights.size() == 1);
  CHECK(ok.lights[0].kind == PunctualKind::Sun);
  CHECK(ok.lights[0].angleDegrees == 2.0f);
  CHECK(load(R"({"type": "sun", "direction": [0, -1, 0], "irradiance": [1, 1, 1]})").lights[0].angleDegrees == 0.53f);
  CHECK_THROWS_WITH_AS(load(R"({"type": "sun", "direction": [0, 0, 0], "irradiance": [1, 1, 1]})"),
                       doctest::Contains("lights[0].direction"), InputError);
  for (const char* angle : {"0", "-1", "180", "200"})
    CHECK_THROWS_WITH_AS(load(std::string(R"({"type": "sun", "direction": [0, -1, 0], "irradiance": [1, 1, 1], "angle": )") + angle + "}"),
                         doctest::Contains("lights[0].angle"), InputError);
  CHECK_THROWS_WITH_AS(load(R"({"type": "sun", "direction": [0, -1, 0], "irradiance": [1, -1, 1]})"),
                       doctest::Contains("lights[0].irradiance"), InputError);
}

}  // namespace test_file_sun_light
