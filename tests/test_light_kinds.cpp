// test_light_kinds.cpp: the light kind table (kernels/shared/light_kinds.h) and its dispatch
// (kernels/stages/direct_light.h), compiled as C++ on a one-triangle emitter under a constant
// environment: light selection gives each kind its share (a binomial z-test), and for every sample
// the dispatch's pdf and radiance at the light the sample reached (light_hit) are the sample's own:
// what MIS against BSDF sampling relies on.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "kernels/shared/rng.h"
#include "kernels/stages/direct_light.h"

namespace test_file_light_kinds {  // keeps this file's helpers apart in a unity batch

namespace {

struct OneEmitter {
  FrameParams f{};
  std::vector<Triangle> tris = std::vector<Triangle>(1);
  std::vector<float4> normals = std::vector<float4>(1);
  std::vector<Material> materials = std::vector<Material>(1);
  std::vector<Emitter> emitters = std::vector<Emitter>(1);
  float4 envMap[1] = {float4(0.0f)};
  float envCdf[1] = {0.0f};

  // A triangle at z = 1 facing down (-z), Le (2, 3, 4); environment radiance (0.5, 0.25, 1) when env.
  explicit OneEmitter(bool env) {
    const float3 v0(-1.0f, -1.0f, 1.0f), e1(0.0f, 2.0f, 0.0f), e2(2.0f, 0.0f, 0.0f);
    tris[0].v0 = with_w(v0, as_float(0u));
    tris[0].e1 = with_w(e1, as_float(0u));
    tris[0].e2 = with_w(e2, as_float(0u));
    const float area = triangle_area_of(e1, e2);
    normals[0] = with_w(triangle_unit_normal(e1, e2), area);
    materials[0].emission = float4(2.0f, 3.0f, 4.0f, 0.0f);
    materials[0].maps = float4(as_float(MCL_NO_TEXTURE), as_float(MCL_NO_TEXTURE), 0.0f, 0.0f);
    emitters[0].tri = 0;
    emitters[0].cdf = 1.0f;
    emitters[0].area = area;
    f.emitterCount = 1;
    f.emitterPower = area * luminance(xyz(materials[0].emission));
    f.environment = env ? float4(0.5f, 0.25f, 1.0f, 1.0f) : float4(0.0f);
    f.shareEnvironment = env ? 0.5f : 0.0f;  // as the host's light table would pick by power
    f.shareArea = env ? 0.5f : 1.0f;
  }
  LightScene scene() const {
    return make_light_scene(tris.data(), normals.data(), materials.data(), emitters.data(), envMap, envCdf, nullptr, nullptr,
                            TextureTables{});
  }
};

}  // namespace

TEST_CASE("light kinds: tags in table order; selection shares; sample pdf and Le equal light_pdf and light_eval" *
          doctest::test_suite("cpu")) {
  CHECK(MCL_LIGHT_environment == 0);
  CHECK(MCL_LIGHT_area == 1);
  CHECK(MCL_LIGHT_point == 2);
  CHECK(MCL_LIGHT_spot == 3);
  CHECK(MCL_LIGHT_directional == 4);
  CHECK(MCL_LIGHT_sun == 5);
  CHECK(MCL_LIGHT_KIND_COUNT == 6);
  for (bool env : {false, true}) {
    CAPTURE(env);
    const OneEmitter s(env);
    const LightScene ls = s.scene();
    CHECK(environment_light_probability(&s.f) + area_light_probability(&s.f) == 1.0f);
    const float3 origin(0.2f, -0.1f, 0.0f);
    const int n = 20000;
    int toEnv = 0, toArea = 0, pdfMismatch = 0, leMismatch = 0;
    for (int i = 0; i < n; ++i) {
      const float4 u = rng_uniform4(23u, uint(i), 0u, 0u);
      const LightSample l = sample_direct_light(&s.f, ls, origin, u);
      if (!(l.pdf > 0.0f)) continue;
      Hit h;
      h.tri = MCL_NO_HIT;
      h.t = INFINITY;
      h.u = h.v = 0.0f;
      if (l.tmax != INFINITY) {  // toward the triangle: where the ray along wi meets it
        float bu = 0.0f, bv = 0.0f;
        const float t = ray_triangle(origin, l.wi, xyz(s.tris[0].v0), xyz(s.tris[0].e1), xyz(s.tris[0].e2),
                                     INFINITY, &bu, &bv);
        REQUIRE(t < INFINITY);
        h.tri = 0;
        h.t = t;
      }
      const LightHit lh = light_hit(h, l.wi);
      (lh.kind == MCL_LIGHT_environment ? toEnv : toArea) += 1;
      const float pdf = light_pdf(&s.f, ls, lh);
      pdfMismatch += !(std::fabs(pdf - l.pdf) <= 1e-3f * l.pdf);
      leMismatch += !(light_eval(&s.f, ls, lh) == l.le);
    }
    CHECK(pdfMismatch == 0);
    CHECK(leMismatch == 0);
    const double pEnv = env ? 0.5 : 0.0;
    CHECK(environment_light_probability(&s.f) == float(pEnv));
    const int picked = toEnv + toArea;  // area samples toward the triangle always count (it faces origin)
    REQUIRE(picked > n / 2);
    const double se = std::sqrt(pEnv * (1.0 - pEnv) / n);
    INFO("environment share " << double(toEnv) / n << ", expected " << pEnv << " +- " << se);
    CHECK(std::fabs(double(toEnv) / n - pEnv) <= 4.0 * se + 1e-9);
  }
}

}  // namespace test_file_light_kinds
