// test_bsdf_coated_diffuse.cpp: the coated_diffuse kind (kernels/shared/bsdf_coated_diffuse.h),
// compiled as C++: its reflectance against the closed form of a clear smooth coat over a Lambertian
// base (white furnace: all light comes back but what the walk's bounce limit cuts), energy <= 1,
// reciprocity of its walk in expectation, the thickness's absorption, and a chi-square test of its
// sampler against its pdf (failing against a wrong pdf).
#include <doctest/doctest.h>

#include <cmath>

#include "bsdf_chi2.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "render/device_materials.h"
#include "stats.h"

namespace test_file_bsdf_coated_diffuse {  // keeps this file's helpers apart in a unity batch

using montecl::MaterialDesc;
using montecl_test::chiDirFromAngles;
using montecl_test::chiSquareCritical;
using montecl_test::chiSquareStat;
using montecl_test::RunningStats;

namespace {

MaterialDesc coated(float base, float alpha, float thickness, int maxDepth = 10, float ior = 1.5f) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_coated_diffuse;
  d.albedo = glm::vec3(base);
  d.kindAlpha = alpha;
  d.thickness = thickness;
  d.layerMaxDepth = maxDepth;
  d.ior = ior;
  return d;
}

Bsdf make(const MaterialDesc& d) { return bsdf_from_material(montecl::deviceMaterial(d), d.albedo); }

// Fresnel reflectance of a smooth dielectric interface, written here again (unpolarised).
double fresnel(double cosI, double eta) {
  const double sin2T = (1.0 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0) return 1.0;
  const double cosT = std::sqrt(1.0 - sin2T);
  const double rs = (cosI - eta * cosT) / (cosI + eta * cosT), rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// The directional reflectance of a smooth clear coat (index eta, no absorption) over a Lambertian
// base rho: F(wo) + (1 - F(wo)) rho (1 - r_i) / (1 - rho r_i), where r_i = 1 - (1 - r_e) / eta^2 is
// the interface's reflectance for diffuse light from inside and r_e the cosine-weighted mean of
// F from outside (the classic layered result: every diffuse bounce inside escapes with 1 - r_i).
double coatedReflectance(double cosO, double rho, double eta) {
  const int n = 20000;
  double re = 0.0;
  for (int i = 0; i < n; ++i) {
    const double c = (i + 0.5) / n;
    re += fresnel(c, eta) * 2.0 * c / n;
  }
  const double ri = 1.0 - (1.0 - re) / (eta * eta);
  return fresnel(cosO, eta) + (1.0 - fresnel(cosO, eta)) * rho * (1.0 - ri) / (1.0 - rho * ri);
}

RunningStats reflectance(const Bsdf& b, float3 wo, int count, std::uint32_t seed) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame();
  RunningStats r;
  for (int i = 0; i < count; ++i) {
    const float4 u = rng_uniform4(seed, uint(i), 1u, 0u);
    const BsdfSample bs = bsdf_sample(b, s, wo, u.x, u.y, u.z);
    r.add(bs.pdf > 0.0f ? double(bs.weight.x) : 0.0);
  }
  return r;
}

}  // namespace

TEST_CASE("coated_diffuse: reflectance is the smooth coat's closed form within 4 SE; a white base reflects ~1, never more" *
          doctest::test_suite("cpu")) {
  for (double rho : {1.0, 0.5})
    for (double thetaO : {0.0, 0.7, 1.3}) {
      // A thin layer (no absorption) and a bounce limit high enough that the walk's series is whole.
      const Bsdf b = make(coated(float(rho), 0.0f, 1e-5f, 200));
      const RunningStats r = reflectance(b, chiDirFromAngles(thetaO, 0.3), 200000, 3u);
      const double expected = coatedReflectance(std::cos(thetaO), rho, 1.5);
      INFO("rho " << rho << " theta_o " << thetaO << ": " << r.mean << " +- " << r.standardError() << ", closed form "
                  << expected);
      CHECK(std::fabs(r.mean - expected) < 4.0 * r.standardError() + 2e-3);  // 2e-3: the GGX coat of alpha 1e-3
      CHECK(r.mean <= 1.0 + 4.0 * r.standardError());
      if (rho == 1.0) CHECK(r.mean > 0.97);  // white furnace: the light comes back
    }
  // pbrt's default bounce limit (10) and thickness (0.01) lose a little: still <= 1, below the thin one.
  const RunningStats limited = reflectance(make(coated(1.0f, 0.0f, 0.01f)), chiDirFromAngles(0.5, 0.0), 100000, 4u);
  CHECK(limited.mean <= 1.0);
  CHECK(limited.mean > 0.8);
  // A thick layer absorbs: exp(-thickness / cos) per crossing.
  const RunningStats thick = reflectance(make(coated(1.0f, 0.0f, 1.0f, 200)), chiDirFromAngles(0.5, 0.0), 100000, 5u);
  CHECK(thick.mean < 0.5 * limited.mean);
}

TEST_CASE("coated_diffuse: f is reciprocal in expectation; the coat's lobe exactly" * doctest::test_suite("cpu")) {
  const Bsdf b = make(coated(0.7f, 0.2f, 0.05f, 20));
  for (int pair = 0; pair < 6; ++pair) {
    const float4 u = rng_uniform4(7u, uint(pair), 0u, 0u);
    const double cosA = 0.1 + 0.9 * u.x, cosB = 0.1 + 0.9 * u.y;
    RunningStats ab, ba;
    for (std::uint32_t i = 0; i < 40000; ++i) {
      RngOut seed = pcg4d(i, uint(pair), 17u, 0u);
      ab.add(double(coated_diffuse_walk(b.p.coated_diffuse, float(cosA), float(cosB), seed, 1).x));
      seed = pcg4d(i, uint(pair), 23u, 0u);
      ba.add(double(coated_diffuse_walk(b.p.coated_diffuse, float(cosB), float(cosA), seed, 1).x));
    }
    const double se = std::sqrt(ab.standardError() * ab.standardError() + ba.standardError() * ba.standardError());
    INFO("cos " << cosA << ", " << cosB << ": " << ab.mean << " vs " << ba.mean << " +- " << se);
    CHECK(std::fabs(ab.mean - ba.mean) < 4.0 * se);
    CHECK(ab.mean > 0.0);
  }
}

TEST_CASE("coated_diffuse: the sampler passes chi-square against its pdf and fails a wrong one" * doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame();
  for (float alpha : {0.1f, 0.3f})
    for (double thetaO : {0.35, 1.1}) {
      const Bsdf b = make(coated(0.6f, alpha, 0.01f)), w = make(coated(0.6f, alpha + 0.1f, 0.01f, 10, 2.0f));
      const float3 wo = chiDirFromAngles(thetaO, 0.4);
      const montecl_test::SamplerChi2 r = montecl_test::samplerChi2(b, w, s, wo);
      const double stat = r.stat, wrong = r.wrong;
      const int dof = r.dof, dofWrong = r.dofWrong;
      INFO("alpha " << alpha << " theta_o " << thetaO << ": chi2 " << stat << " dof " << dof << "; wrong " << wrong);
      CHECK(stat < chiSquareCritical(dof));
      CHECK(wrong > chiSquareCritical(dofWrong));
    }
}

TEST_CASE("coated_diffuse: the layer's exp(-x) of + and * only is std::exp within 2e-7 (1 + x) relative, 0 far out" *
          doctest::test_suite("cpu")) {
  for (double x = 0.0; x < 80.0; x += 0.0173) {
    const double want = std::exp(-x), got = double(mcl_exp_neg(float(x)));
    CAPTURE(x);
    CHECK(std::fabs(got - want) <= 2e-7 * (1.0 + x) * want + 1e-38);  // x * 1.44 rounded to float: ~x ulp
  }
  for (float x : {100.0f, 1e6f, 1e20f, 3e38f}) CHECK(mcl_exp_neg(x) == 0.0f);
}

}  // namespace test_file_bsdf_coated_diffuse
