// test_bsdf_clearcoat.cpp: glTF's KHR_materials_clearcoat on the metal_rough kind
// (kernels/shared/bsdf_metal_rough.h), compiled as C++: f cos is the extension's layering
// mix(base, coat GGX, c x Fc(n.wo)) exactly; the reflectance of a smooth coat over a smooth black
// base (F0 0.04 or 0) is its closed form c F + (1 - c F) F_base (the one-bounce white furnace,
// estimated from the kind's own samples, by z-score); a white metal under a rough coat reflects at
// most 1.
#include <doctest/doctest.h>

#include <cmath>

#include "bsdf_chi2.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "render/device_materials.h"
#include "stats.h"

namespace test_file_bsdf_clearcoat {  // keeps this file's helpers apart in a unity batch

using montecl::MaterialDesc;
using montecl_test::chiDirFromAngles;
using montecl_test::RunningStats;

namespace {

MaterialDesc coated(glm::vec3 base, float metallic, float roughness, float coat, float coatRoughness) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_metal_rough;
  d.albedo = base, d.metallic = metallic, d.roughness = roughness;
  d.clearcoat = coat, d.clearcoatRoughness = coatRoughness;
  return d;
}
Bsdf make(const MaterialDesc& d) { return bsdf_from_material(montecl::deviceMaterial(d), float3(d.albedo.x, d.albedo.y, d.albedo.z)); }

// Schlick's term of F0 at cosine c.
double schlick(double f0, double c) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

}  // namespace

TEST_CASE("clearcoat: f cos is mix(base, coat GGX, c x Fc(n.wo)), Fc Schlick of IOR 1.5" * doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  const MaterialDesc base = coated(glm::vec3(0.7f, 0.4f, 0.2f), 0.3f, 0.6f, 0.0f, 0.0f);
  for (float c : {1.0f, 0.4f}) {
    MaterialDesc d = base;
    d.clearcoat = c, d.clearcoatRoughness = 0.35f;
    const Bsdf b = make(d), u = make(base);
    int off = 0;
    for (int i = 0; i < 2000; ++i) {
      const float4 r = rng_uniform4(11u, uint(i), 0u, 0u);
      const float3 wo = chiDirFromAngles(std::acos(double(r.x)), 6.283 * r.y), wi = chiDirFromAngles(std::acos(double(r.z)), 6.283 * r.w);
      const double w = c * schlick(0.04, double(wo.z));
      const double g = ggx_eval_cos(wo, wi, 0.35f * 0.35f);
      const float3 fc = bsdf_eval(b, s, wo, wi), fu = bsdf_eval(u, s, wo, wi);
      for (int k = 0; k < 3; ++k) {
        const double want = (1.0 - w) * double(fu[k]) + w * g;
        off += std::fabs(double(fc[k]) - want) > 1e-5 * std::max(1.0, want);
      }
    }
    INFO("coat " << c);
    CHECK(off == 0);
  }
}

// A smooth coat (roughness 0: GGX alpha 1e-3) over a smooth black base: the base is Schlick's
// specular alone, F_base = F(0.04) (metallic 0) or (1 - cos)^5 (metallic 1, base 0), so one bounce
// under a white sky reflects c F + (1 - c F) F_base with F = Fc = Schlick(0.04). The estimate is the
// mean sample weight (the kind's sampler, its pdf, its eval); a near-mirror GGX lobe of alpha 1e-3
// loses Lambda ~ alpha^2 tan^2 / 4 < 1e-5 at these angles and its half vectors move F(v.h) off
// F(n.v) by about alpha: the bound allows 1e-4 beside the z-score (the weights barely vary).
TEST_CASE("clearcoat: a smooth coat over a smooth black base reflects c F + (1 - c F) F_base (closed form)" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  for (float metallic : {0.0f, 1.0f})
    for (float c : {1.0f, 0.5f}) {
      const Bsdf b = make(coated(glm::vec3(0.0f), metallic, 0.0f, c, 0.0f));
      for (double theta : {0.0, 0.6, 1.1, 1.35}) {
        const float3 wo = chiDirFromAngles(theta, 0.3);
        const double cosO = std::cos(theta), f = schlick(0.04, cosO);
        const double fBase = metallic > 0.0f ? schlick(0.0, cosO) : f;
        const double want = c * f + (1.0 - c * f) * fBase;
        const RunningStats r = montecl_test::sampledReflectance(b, s, wo, 20000, 13u, 0);
        INFO("metallic " << metallic << " coat " << c << " theta " << theta << ": " << r.mean << " +- "
                         << r.standardError() << ", closed form " << want);
        CHECK(std::fabs(r.mean - want) <= 4.0 * r.standardError() + 1e-4);
      }
    }
}

TEST_CASE("clearcoat: a white metal under a rough coat reflects at most 1, and more than the coat alone" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  const Bsdf b = make(coated(glm::vec3(1.0f), 1.0f, 0.4f, 1.0f, 0.5f));
  for (double theta : {0.0, 0.8, 1.4}) {
    const float3 wo = chiDirFromAngles(theta, 1.0);
    const RunningStats r = montecl_test::sampledReflectance(b, s, wo, 100000, 17u, 1);
    INFO("theta " << theta << ": reflectance " << r.mean << " +- " << r.standardError());
    CHECK(r.mean <= 1.0 + 4.0 * r.standardError());
    CHECK(r.mean > 0.8);  // F = 1 under a coat of weight <= Fc: most of it comes back
  }
}

}  // namespace test_file_bsdf_clearcoat
