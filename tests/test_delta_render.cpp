// test_delta_render.cpp: the delta lobes through the real kernels: a closed glass cube (smooth
// dielectric, both interfaces, total internal reflection) under a constant environment E with the
// path integrator at unlimited depth shows E (energy is conserved: the 1 / eta^2 in and eta^2 out
// cancel) within 4 standard errors; a perfect mirror cube (conductor, F = 1) shows E exactly (zero
// variance: no MIS weight after a delta bounce, no light sample at a delta surface) with path and
// with the direct integrator's brdf and mis strategies, and 0 with light sampling alone (a delta
// lobe cannot be reached by a light sample); a thin sheet under E shows E exactly.
#include <doctest/doctest.h>

#include <cmath>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "film_stats.h"
#include "render/wavefront.h"
#include "scene/render_choices.h"
#include "test_scenes.h"

namespace test_file_delta_render {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

const glm::vec3 kE(1.0f, 0.5f, 0.25f);

Film renderWith(Scene scene, Integrator integrator, const char* strategy, int maxDepth) {
  static const DeviceInfo device = selectDevice("");
  scene.render.integrator = integrator;
  if (strategy) scene.render.directSampling = directSamplingNames().at(strategy);
  scene.render.maxDepth = maxDepth;
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

// A unit cube of material m, rotated so several faces are seen, under the constant environment kE;
// with `sheet` only its front face (a single open quad).
Scene cubeScene(const MaterialDesc& m, bool sheet) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<delta cube>";
  s.materials = {m};
  const float h = 0.5f;
  const glm::vec3 p[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h},
                          {-h, -h, h},  {h, -h, h},  {h, h, h},  {-h, h, h}};
  addQuad(s, p[4], p[5], p[6], p[7]);
  if (!sheet) {
    addQuad(s, p[1], p[0], p[3], p[2]);
    addQuad(s, p[5], p[1], p[2], p[6]);
    addQuad(s, p[0], p[4], p[7], p[3]);
    addQuad(s, p[7], p[6], p[2], p[3]);
    addQuad(s, p[0], p[1], p[5], p[4]);
  }
  s.camera.position = {1.2f, 1.0f, 2.5f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = 30.0f;
  s.camera.width = s.camera.height = 8;
  s.render.spp = 256;
  s.environment.enabled = true;
  s.environment.radiance = kE;
  finishScene(s);
  return s;
}

MaterialDesc kindDesc(std::uint32_t kind) {
  MaterialDesc d;
  d.kind = kind;
  d.ior = 1.5f;
  d.eta = glm::vec3(0.0f), d.k = glm::vec3(1.0f);  // conductor: F = 1
  return d;
}

}  // namespace

TEST_CASE("delta: a closed glass cube under a constant environment shows it (path, unlimited depth)" *
          doctest::test_suite("opencl")) {
  for (std::uint32_t kind : {std::uint32_t(MCL_MATERIAL_dielectric), std::uint32_t(MCL_MATERIAL_thin_dielectric)}) {
    const Film f = renderWith(cubeScene(kindDesc(kind), kind == MCL_MATERIAL_thin_dielectric), Integrator::Path, nullptr, -1);
    for (int c = 0; c < 3; ++c) {
      const ImageEstimate e = imageEstimate(f, c);
      INFO("kind " << kind << " channel " << c << ": " << e.mean << " +- " << e.standardError);
      // The sheet's weights are all 1 (each lobe picked with its own share): E exactly. The cube's
      // refractions weigh 1 / eta^2 and eta^2: E in expectation.
      if (kind == MCL_MATERIAL_thin_dielectric) CHECK(std::fabs(e.mean - kE[c]) < 1e-5);
      else {
        CHECK(e.standardError > 0.0);
        CHECK(std::fabs(e.mean - kE[c]) < 4.0 * e.standardError);
      }
    }
  }
}

TEST_CASE("delta: a perfect mirror cube shows the environment exactly (path; direct brdf and mis), light alone 0" *
          doctest::test_suite("opencl")) {
  const Scene s = cubeScene(kindDesc(MCL_MATERIAL_conductor), false);
  const Film path = renderWith(s, Integrator::Path, nullptr, 5);
  const Film brdf = renderWith(s, Integrator::Direct, "brdf", -1);
  const Film mis = renderWith(s, Integrator::Direct, "mis", -1);
  const Film light = renderWith(s, Integrator::Direct, "light", -1);
  int off = 0, black = 0;
  for (std::size_t p = 0; p < path.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      off += std::fabs(path.meanOf(p, c) - kE[c]) > 1e-5 || std::fabs(brdf.meanOf(p, c) - kE[c]) > 1e-5 ||
             std::fabs(mis.meanOf(p, c) - kE[c]) > 1e-5;
      black += light.meanOf(p, c) == 0.0;  // pixels wholly on the mirror (edge pixels mix in misses)
    }
  CHECK(off == 0);
  CHECK(black > int(path.mean.size()));  // over a third of the pixel channels
}

}  // namespace test_file_delta_render
