// test_rough_glass_render.cpp: the rough dielectric through the real kernels: a camera looks up
// through a rough glass pane at an emitting quad just above it, from the pane's outside and
// (flipped pane) from its inside. Every way of estimating that image must agree within 4 standard
// errors: direct light sampling alone (next-event estimation toward a light below the surface, seen
// through the transmitted lobe: the shading cosine is the BSDF's |cos| and the shadow ray leaves
// from the far side, aimed at the sampled light point), BSDF sampling alone, MIS, and the path
// integrator at depth 2 (the same estimator as direct MIS).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "film_stats.h"
#include "render/wavefront.h"
#include "scene/render_choices.h"
#include "test_scenes.h"

namespace test_file_rough_glass_render {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

Film renderWith(Scene scene, Integrator integrator, const char* strategy, int maxDepth) {
  static const DeviceInfo device = selectDevice("");
  scene.render.integrator = integrator;
  scene.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  if (strategy) scene.render.directSampling = directSamplingNames().at(strategy);
  scene.render.maxDepth = maxDepth;
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

// An emitter (y = 1, facing down) 0.1 above a rough glass pane of alpha 0.3 (front face down, or up
// when flipped); the camera below looks up through the pane.
Scene paneScene(bool flipped) {
  Scene s;
  s.path = "<rough glass pane>";
  MaterialDesc glass;
  glass.kind = MCL_MATERIAL_dielectric;
  glass.ior = 1.5f;
  glass.kindAlpha = 0.3f;
  MaterialDesc light;
  light.albedo = glm::vec3(0.0f);
  light.emission = glm::vec3(4.0f, 2.0f, 1.0f);
  s.materials = {glass, light};
  const float h = 0.5f, w = 1.5f;
  addQuad(s, {-h, 1.0f, -h}, {h, 1.0f, -h}, {h, 1.0f, h}, {-h, 1.0f, h}, 1);  // cross(b - a, c - a) = -y
  if (flipped) addQuad(s, {-w, 0.9f, -w}, {-w, 0.9f, w}, {w, 0.9f, w}, {w, 0.9f, -w}, 0);
  else addQuad(s, {-w, 0.9f, -w}, {w, 0.9f, -w}, {w, 0.9f, w}, {-w, 0.9f, w}, 0);
  s.camera.position = {0.3f, 0.0f, 0.4f};
  s.camera.target = {0.0f, 0.9f, 0.0f};
  s.camera.up = {0.0f, 0.0f, 1.0f};
  s.camera.fovY = 50.0f;
  s.camera.width = s.camera.height = 12;
  s.render.spp = 1024;
  finishScene(s);
  return s;
}

}  // namespace

TEST_CASE("rough glass: a light seen through a rough pane: light sampling, BSDF sampling, MIS and path depth 2 agree" *
          doctest::test_suite("opencl")) {
  for (bool flipped : {false, true}) {
    const Scene s = paneScene(flipped);
    const Film light = renderWith(s, Integrator::Direct, "light", -1);
    const Film brdf = renderWith(s, Integrator::Direct, "brdf", -1);
    const Film mis = renderWith(s, Integrator::Direct, "mis", -1);
    const Film path = renderWith(s, Integrator::Path, nullptr, 2);
    for (int c = 0; c < 3; ++c) {
      const ImageEstimate l = imageEstimate(light, c), b = imageEstimate(brdf, c), m = imageEstimate(mis, c),
                          p = imageEstimate(path, c);
      INFO(std::string(flipped ? "from inside" : "from outside") << ", channel " << c << ": light " << l.mean << " +- "
                                                      << l.standardError << ", brdf " << b.mean << " +- "
                                                      << b.standardError << ", mis " << m.mean << " +- "
                                                      << m.standardError << ", path " << p.mean << " +- "
                                                      << p.standardError);
      CHECK(b.mean > 0.01);  // the light is seen through the pane
      CHECK(std::fabs(l.mean - b.mean) < 4.0 * std::hypot(l.standardError, b.standardError));
      CHECK(std::fabs(m.mean - b.mean) < 4.0 * std::hypot(m.standardError, b.standardError));
      CHECK(std::fabs(p.mean - m.mean) < 4.0 * std::hypot(p.standardError, m.standardError));
    }
  }
}

}  // namespace test_file_rough_glass_render
