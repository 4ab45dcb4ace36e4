// test_punctual_lights.cpp: point, spot and directional lights (kernels/shared/light_point.h,
// light_spot.h, light_directional.h) through the real kernels, against closed forms on a diffuse
// floor (albedo rho): a point light of intensity I at height h gives rho/pi I cos^3(theta) / h^2,
// a directional light rho/pi E cos(theta), a spot the point's value times Mitsuba 3's falloff.
// With one delta light every sample has the same value, so those are checked to 1e-4 per pixel;
// with several lights the selection by power is checked with a z-test. BRDF-only direct sampling
// cannot reach a delta light (0), and AO ignores them.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "film_stats.h"
#include "render/wavefront.h"
#include "scene/builtin_scenes.h"

namespace test_file_punctual_lights {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
const glm::vec3 kRho(0.5f, 0.6f, 0.7f);

// A 4 x 4 floor y = 0 (albedo kRho) seen straight down from 0.05 above `at` through a 0.01 degree
// field of view (every pixel sees `at` to 1e-5), lit by `lights`.
Scene floorUnder(glm::vec3 at, std::vector<LightDesc> lights, Integrator integrator, int spp = 4) {
  Scene s;
  s.path = "<floor under punctual lights>";
  s.materials = {MaterialDesc{"floor", kRho, glm::vec3(0.0f)}};
  addQuad(s, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, 0);
  s.camera.position = at + glm::vec3(0, 0.05f, 0);
  s.camera.target = at;
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 0.01f;
  s.camera.width = s.camera.height = 3;
  s.render.spp = spp;
  s.render.integrator = integrator;
  s.render.maxDepth = 3;
  s.lights = std::move(lights);
  finishScene(s);
  return s;
}

Film render(const Scene& scene, DirectSampling strategy = DirectSampling::Mis) {
  static const DeviceInfo device = selectDevice("");
  Scene s = scene;
  s.render.directSampling = strategy;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(s, bvh, stats);
}

LightDesc pointAt(glm::vec3 p, glm::vec3 intensity) {
  LightDesc l;
  l.position = p;
  l.color = intensity;
  return l;
}

// Every pixel, every channel within a relative 1e-4 of expected[c]: float precision, the pixel
// footprint (1e-5) and the shadow ray's origin offset off the surface (about 2e-5).
void checkEveryPixel(const Film& f, glm::dvec3 expected, const char* what) {
  int bad = 0;
  for (std::size_t p = 0; p < f.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double got = f.meanOf(p, c);
      if (!(std::fabs(got - expected[c]) <= 1e-4 * expected[c] + 1e-12)) {
        if (bad++ < 3) MESSAGE(what << ": pixel " << p << " channel " << c << ": " << got << ", expected " << expected[c]);
      }
    }
  CHECK_MESSAGE(bad == 0, what);
}

}  // namespace

TEST_CASE("punctual lights: a point light gives rho/pi I cos^3 / h^2 exactly, direct and path" *
          doctest::test_suite("opencl")) {
  const glm::vec3 I(2.0f, 3.0f, 5.0f);
  const double h = 1.3;
  for (double d : {0.0, 0.4, 1.1}) {
    const double cos3 = std::pow(h / std::sqrt(h * h + d * d), 3.0);
    const glm::dvec3 expected = glm::dvec3(kRho) / kPi * glm::dvec3(I) * (cos3 / (h * h));
    const std::vector<LightDesc> lights = {pointAt({0.0f, float(h), 0.0f}, I)};
    CAPTURE(d);
    checkEveryPixel(render(floorUnder({float(d), 0, 0}, lights, Integrator::Direct)), expected, "direct mis");
    checkEveryPixel(render(floorUnder({float(d), 0, 0}, lights, Integrator::Direct), DirectSampling::Light), expected,
                    "direct light");
    checkEveryPixel(render(floorUnder({float(d), 0, 0}, lights, Integrator::Path)), expected, "path");
    // A BSDF ray never reaches a delta light; AO does not see lights.
    checkEveryPixel(render(floorUnder({float(d), 0, 0}, lights, Integrator::Direct), DirectSampling::Brdf),
                    glm::dvec3(0.0), "direct brdf");
  }
}

TEST_CASE("punctual lights: a directional light gives rho/pi E cos(theta); a spot light the point's value "
          "inside its beam, Mitsuba's linear falloff between beam and cutoff, 0 outside" *
          doctest::test_suite("opencl")) {
  const glm::vec3 E(0.7f, 0.4f, 0.2f);
  for (double deg : {0.0, 35.0, 70.0}) {
    const double a = deg * kPi / 180.0;
    LightDesc sun;
    sun.kind = PunctualKind::Directional;
    sun.direction = glm::vec3(float(std::sin(a)), float(-std::cos(a)), 0.0f);
    sun.color = E;
    CAPTURE(deg);
    const glm::dvec3 expected = glm::dvec3(kRho) / kPi * glm::dvec3(E) * std::cos(a);
    for (Integrator integ : {Integrator::Direct, Integrator::Path})
      checkEveryPixel(render(floorUnder({0.2f, 0, -0.1f}, {sun}, integ)), expected, "directional");
  }
  const glm::vec3 I(4.0f, 2.0f, 1.0f);
  const double h = 1.0;
  LightDesc spot = pointAt({0.0f, float(h), 0.0f}, I);
  spot.kind = PunctualKind::Spot;
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.cutoffDegrees = 30.0f;
  spot.beamDegrees = 20.0f;
  struct Case {
    double deg, falloff;
  };
  for (Case c : {Case{0.0, 1.0}, Case{12.0, 1.0}, Case{25.0, 0.5}, Case{27.5, 0.25}, Case{40.0, 0.0}}) {
    const double d = h * std::tan(c.deg * kPi / 180.0), cosT = h / std::sqrt(h * h + d * d);
    const glm::dvec3 expected = glm::dvec3(kRho) / kPi * glm::dvec3(I) * (c.falloff * cosT * cosT * cosT / (h * h));
    CAPTURE(c.deg);
    const Film f = render(floorUnder({float(d), 0, 0}, {spot}, Integrator::Direct));
    if (c.falloff == 1.0 || c.falloff == 0.0) {
      checkEveryPixel(f, expected, "spot");
    } else {  // acos in float near the ramp: a looser bound
      for (int ch = 0; ch < 3; ++ch) CHECK(std::fabs(imageMean(f, ch) - expected[ch]) <= 2e-3 * expected[ch]);
    }
  }
}

TEST_CASE("punctual lights: with a point, a spot and a directional light, selection by power averages to the sum "
          "of each alone (z-test)" *
          doctest::test_suite("opencl")) {
  LightDesc point = pointAt({0.3f, 1.0f, 0.0f}, {1.0f, 2.0f, 3.0f});
  LightDesc spot = pointAt({-0.2f, 1.5f, 0.1f}, {6.0f, 3.0f, 1.0f});
  spot.kind = PunctualKind::Spot;
  spot.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.0f));
  spot.cutoffDegrees = 40.0f;
  spot.beamDegrees = 30.0f;
  LightDesc sun;
  sun.kind = PunctualKind::Directional;
  sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.2f));
  sun.color = {0.5f, 0.4f, 0.3f};
  const glm::vec3 at(0.1f, 0.0f, 0.05f);
  glm::dvec3 sum(0.0);
  for (const LightDesc& l : {point, spot, sun})
    for (int c = 0; c < 3; ++c) sum[c] += imageMean(render(floorUnder(at, {l}, Integrator::Direct)), c);
  const Film all = render(floorUnder(at, {point, spot, sun}, Integrator::Direct, 2048));
  for (int c = 0; c < 3; ++c) {
    const ImageEstimate e = imageEstimate(all, c);
    CAPTURE(c);
    INFO("all three " << e.mean << " +- " << e.standardError << ", sum of each alone " << sum[c]);
    CHECK(e.standardError > 0.0);
    CHECK(std::fabs(e.mean - sum[c]) <= 4.0 * e.standardError);
  }
}

}  // namespace test_file_punctual_lights
