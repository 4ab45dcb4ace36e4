// test_bsdf_sheen.cpp: glTF's KHR_materials_sheen on the metal_rough kind (kernels/shared/sheen.h,
// bsdf_metal_rough.h), compiled as C++: f cos is sheenColor x the Charlie lobe (D and Estevez and
// Kulla's visibility, written out in double precision in fixtures/charlie_sheen.h) + (1 -
// max(sheenColor) E(n.wo)) x the plain BRDF; the albedo fit E is within its stated error of the
// lobe's albedo integrated there; a
// white sheen over a white base reflects at most 1 (its fit error aside) and exactly the layering's
// closed form E_true + (1 - E) A_base (z-test of the kind's own samples); sheen under a coat is
// the coat's mix of the sheened BRDF.
#include <doctest/doctest.h>

#include <cmath>

#include "bsdf_chi2.h"
#include "charlie_sheen.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "render/device_materials.h"
#include "stats.h"

namespace test_file_bsdf_sheen {  // keeps this file's helpers apart in a unity batch

using montecl::MaterialDesc;
using montecl_test::chiDirFromAngles;
using montecl_test::RunningStats;

namespace {

MaterialDesc sheened(glm::vec3 base, float metallic, float roughness, glm::vec3 sheen, float sheenRoughness) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_metal_rough;
  d.albedo = base, d.metallic = metallic, d.roughness = roughness;
  d.sheenColor = sheen, d.sheenRoughness = sheenRoughness;
  return d;
}
Bsdf make(const MaterialDesc& d) { return bsdf_from_material(montecl::deviceMaterial(d), float3(d.albedo.x, d.albedo.y, d.albedo.z)); }

// f cos of the sheen lobe of colour 1 (charlie_sheen.h, in double precision).
double lobeCos(float3 wo, float3 wi, double r) {
  const double o[3] = {wo.x, wo.y, wo.z}, i[3] = {wi.x, wi.y, wi.z};
  return montecl_test::charlieLobeCos(o, i, r);
}
double lobeAlbedo(double mu, double r) { return montecl_test::charlieAlbedo(mu, r); }

}  // namespace

TEST_CASE("sheen: f cos is c x Charlie D V cos + (1 - max(c) E(n.wo)) x the plain BRDF" * doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  for (const float r : {0.3f, 0.7f, 1.0f}) {
    const glm::vec3 c(0.9f, 0.5f, 0.2f);
    const MaterialDesc plain = sheened(glm::vec3(0.3f, 0.6f, 0.8f), 0.2f, 0.5f, glm::vec3(0.0f), 0.0f);
    MaterialDesc d = plain;
    d.sheenColor = c, d.sheenRoughness = r;
    const Bsdf b = make(d), u = make(plain);
    int off = 0, checked = 0;
    for (int i = 0; i < 2000; ++i) {
      const float4 q = rng_uniform4(23u, uint(i), 0u, 0u);
      const float3 wo = chiDirFromAngles(std::acos(double(q.x)), 6.283 * q.y), wi = chiDirFromAngles(std::acos(double(q.z)), 6.283 * q.w);
      const double scale = std::min(std::max(1.0 - 0.9 * double(sheen_albedo(wo.z, r)), 0.0), 1.0);
      const double lobe = lobeCos(wo, wi, r);
      const float3 fs = bsdf_eval(b, s, wo, wi), fu = bsdf_eval(u, s, wo, wi);
      for (int k = 0; k < 3; ++k) {
        const double want = double(c[k]) * lobe + scale * double(fu[k]);
        off += std::fabs(double(fs[k]) - want) > 1e-4 * std::max(1e-3, want);
        ++checked;
      }
    }
    INFO("sheen roughness " << r << ": " << off << " of " << checked << " values off");
    CHECK(off == 0);
  }
}

// The fit's stated error (sheen.h): within 0.03 at every view (the grazing end, mu = 0.002, is its
// worst), 0.02 from mu = 0.05 and 0.011 from mu = 0.1 up, over r in [0.15, 1]; below 0.15 it is
// E(mu, 0.15), above the true albedo away from grazing views.
TEST_CASE("sheen: the albedo fit E is within its stated error of the lobe's albedo (quadrature)" * doctest::test_suite("cpu")) {
  double worst = 0.0;
  for (const double r : {0.15, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0})
    for (const double mu : {0.002, 0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.9, 1.0}) {
      const double want = lobeAlbedo(mu, r), got = sheen_albedo(float(mu), float(r));
      INFO("r " << r << " mu " << mu << ": fit " << got << ", quadrature " << want);
      CHECK(std::fabs(got - want) <= (mu < 0.05 ? 0.03 : mu < 0.1 ? 0.02 : 0.011));
      worst = std::max(worst, std::fabs(got - want));
    }
  MESSAGE("largest |E fit - E| " << worst);
  for (const double r : {0.0, 0.05, 0.1})
    for (const double mu : {0.2, 0.5, 0.9}) {
      INFO("r " << r << " mu " << mu);
      CHECK(sheen_albedo(float(mu), float(r)) == sheen_albedo(float(mu), 0.15f));
      CHECK(double(sheen_albedo(float(mu), float(r))) >= lobeAlbedo(mu, r) - 0.011);
    }
}

// One bounce under a white sky (the kind's own samples, pdf and eval): a white sheen over a white
// metal (F = 1) reflects E_true(mu) + (1 - E(mu)) A_base(mu), A_base the plain metal's reflectance
// (estimated the same way), and so at most 1 + (E_true - E) <= 1 + the fit's error.
TEST_CASE("sheen: a white sheen over a white base reflects E + (1 - E) A_base, at most 1 (white furnace)" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  for (const float r : {0.3f, 0.6f, 1.0f})
    for (const float baseRough : {0.2f, 0.8f}) {
      const Bsdf b = make(sheened(glm::vec3(1.0f), 1.0f, baseRough, glm::vec3(1.0f), r));
      const Bsdf plain = make(sheened(glm::vec3(1.0f), 1.0f, baseRough, glm::vec3(0.0f), 0.0f));
      for (const double theta : {0.0, 0.7, 1.2}) {
        const float3 wo = chiDirFromAngles(theta, 0.5);
        const RunningStats got = montecl_test::sampledReflectance(b, s, wo, 60000, 29u, 0);
        const RunningStats base = montecl_test::sampledReflectance(plain, s, wo, 60000, 31u, 0);
        const double e = sheen_albedo(wo.z, r), eTrue = lobeAlbedo(wo.z, r);
        const double want = eTrue + (1.0 - e) * base.mean;
        const double se = std::sqrt(got.standardError() * got.standardError() +
                                    (1.0 - e) * (1.0 - e) * base.standardError() * base.standardError());
        INFO("r " << r << " base roughness " << baseRough << " theta " << theta << ": " << got.mean << " +- "
                  << got.standardError() << ", closed form " << want << " (E fit " << e << ", true " << eTrue << ")");
        CHECK(std::fabs(got.mean - want) <= 4.0 * se + 2e-3);  // 2e-3: the quadrature of E_true
        CHECK(got.mean <= 1.0 + std::max(eTrue - e, 0.0) + 4.0 * got.standardError());
        CHECK(got.mean > base.mean - 0.02);  // the sheen gives back about what it takes from the base
      }
    }
}

// glTF layers the clearcoat over the sheen: the coated, sheened BRDF is mix(sheened, coat GGX, c Fc).
TEST_CASE("sheen: under a clearcoat the coat mixes the sheened BRDF" * doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  const MaterialDesc sheen = sheened(glm::vec3(0.5f, 0.3f, 0.2f), 0.0f, 0.7f, glm::vec3(0.8f, 0.8f, 1.0f), 0.4f);
  MaterialDesc both = sheen;
  both.clearcoat = 0.7f, both.clearcoatRoughness = 0.3f;
  const Bsdf b = make(both), u = make(sheen);
  int off = 0;
  for (int i = 0; i < 1000; ++i) {
    const float4 q = rng_uniform4(37u, uint(i), 0u, 0u);
    const float3 wo = chiDirFromAngles(std::acos(double(q.x)), 6.283 * q.y), wi = chiDirFromAngles(std::acos(double(q.z)), 6.283 * q.w);
    const double m = 1.0 - double(wo.z);
    const double w = 0.7 * (0.04 + 0.96 * m * m * m * m * m);
    const double g = ggx_eval_cos(wo, wi, 0.3f * 0.3f);
    const float3 fb = bsdf_eval(b, s, wo, wi), fu = bsdf_eval(u, s, wo, wi);
    for (int k = 0; k < 3; ++k) {
      const double want = (1.0 - w) * double(fu[k]) + w * g;
      off += std::fabs(double(fb[k]) - want) > 1e-5 * std::max(1.0, want);
    }
  }
  CHECK(off == 0);
}

}  // namespace test_file_bsdf_sheen
