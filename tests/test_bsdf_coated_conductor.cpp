// test_bsdf_coated_conductor.cpp: the coated_conductor kind (kernels/shared/bsdf_coated_conductor.h),
// compiled as C++: its reflectance against the closed form of a smooth clear coat over a smooth
// metal (a geometric series of internal reflections; the white furnace when the metal reflects
// everything), energy <= 1 over a rough metal, the thickness's absorption, reciprocity of its walk
// in expectation, and a chi-square test of its sampler against its pdf (failing against a wrong pdf).
#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "bsdf_chi2.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "render/device_materials.h"
#include "stats.h"

namespace test_file_bsdf_coated_conductor {  // keeps this file's helpers apart in a unity batch

using montecl::MaterialDesc;
using montecl_test::chiDirFromAngles;
using montecl_test::chiSquareCritical;
using montecl_test::chiSquareStat;
using montecl_test::RunningStats;

namespace {

const glm::vec3 kGoldEta(0.143f, 0.375f, 1.442f), kGoldK(3.983f, 2.386f, 1.603f);

MaterialDesc coatedMetal(glm::vec3 eta, glm::vec3 k, float baseAlpha, float coatAlpha, float thickness,
                         int maxDepth = 10, float ior = 1.5f) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_coated_conductor;
  d.eta = eta;
  d.k = k;
  d.baseAlpha = baseAlpha;
  d.kindAlpha = coatAlpha;
  d.thickness = thickness;
  d.layerMaxDepth = maxDepth;
  d.ior = ior;
  return d;
}

Bsdf makeCc(const MaterialDesc& d) { return bsdf_from_material(montecl::deviceMaterial(d), d.albedo); }

// Fresnel reflectance of a smooth interface for an index n (complex for a metal) relative to the
// incident side, written here again from the complex amplitudes (unpolarised).
double fresnelComplex(double cosI, std::complex<double> n) {
  const std::complex<double> sin2T = (1.0 - cosI * cosI) / (n * n);
  const std::complex<double> cosT = std::sqrt(1.0 - sin2T);
  const std::complex<double> rs = (cosI - n * cosT) / (cosI + n * cosT), rp = (n * cosI - cosT) / (n * cosI + cosT);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

// The directional reflectance of a smooth clear coat (index eta, no absorption) over a smooth metal
// of index (m + i k) / eta relative to the coat: all of it in the mirror direction, the coat's F plus
// light that enters (1 - F), meets the metal (A = its F at the refracted angle), escapes (1 - F) or
// goes round again (F A): F + (1 - F)^2 A / (1 - F A). A layer of some thickness multiplies A by
// its transmittance down and up, exp(-2 thickness / cos_t).
double coatedMetalReflectance(double cosO, double eta, double m, double k, double thickness = 0.0) {
  const double f = fresnelComplex(cosO, eta);
  const double cosT = std::sqrt(1.0 - (1.0 - cosO * cosO) / (eta * eta));
  const double a = fresnelComplex(cosT, std::complex<double>(m, k) / eta) * std::exp(-2.0 * thickness / cosT);
  return f + (1.0 - f) * (1.0 - f) * a / (1.0 - f * a);
}

RunningStats reflectanceCc(const Bsdf& b, float3 wo, int channel, int count, std::uint32_t seed) {
  return montecl_test::sampledReflectance(b, montecl_test::flatBsdfFrame(), wo, count, seed, channel);
}

}  // namespace

TEST_CASE("coated_conductor: reflectance over a smooth metal is the closed form within 4 SE; a perfect mirror's is ~1" *
          doctest::test_suite("cpu")) {
  for (int metal = 0; metal < 2; ++metal)
    for (double thetaO : {0.0, 0.7, 1.3}) {
      // A thin layer (no absorption) and a bounce limit high enough that the series is whole.
      const glm::vec3 eta = metal == 0 ? glm::vec3(0.0f) : kGoldEta, k = metal == 0 ? glm::vec3(1.0f) : kGoldK;
      const Bsdf b = makeCc(coatedMetal(eta, k, 0.0f, 0.0f, 1e-5f, 200));
      for (int c = 0; c < 3; ++c) {
        const RunningStats r = reflectanceCc(b, chiDirFromAngles(thetaO, 0.3), c, 100000, 3u);
        const double expected = coatedMetalReflectance(std::cos(thetaO), 1.5, eta[c], k[c]);
        INFO((metal ? "gold" : "perfect mirror") << ", channel " << c << ", theta_o " << thetaO << ": " << r.mean
                                                 << " +- " << r.standardError() << ", closed form " << expected);
        CHECK(std::fabs(r.mean - expected) < 4.0 * r.standardError() + 3e-3);  // 3e-3: the GGX lobes of alpha 1e-3
        CHECK(r.mean <= 1.0 + 4.0 * r.standardError());
        if (metal == 0) CHECK(r.mean > 0.99);  // white furnace: the light comes back
      }
    }
  // The layer's absorption: the same series with exp(-2 thickness / cos_t) per round.
  for (double thetaO : {0.0, 0.9}) {
    const Bsdf b = makeCc(coatedMetal(kGoldEta, kGoldK, 0.0f, 0.0f, 0.1f, 200));
    const RunningStats r = reflectanceCc(b, chiDirFromAngles(thetaO, 0.3), 0, 100000, 6u);
    const double expected = coatedMetalReflectance(std::cos(thetaO), 1.5, kGoldEta[0], kGoldK[0], 0.1);
    INFO("gold under a layer 0.1 thick, theta_o " << thetaO << ": " << r.mean << " +- " << r.standardError()
                                                  << ", closed form " << expected);
    CHECK(std::fabs(r.mean - expected) < 4.0 * r.standardError() + 3e-3);
  }
  // A rough metal loses what single-scattering GGX loses, never gains: light turned beyond the
  // critical angle stays in the layer for many bounces near grazing, where the loss is largest
  // (0.755 here for a perfect mirror of alpha 0.3 under a coat of 0.2). A thick layer absorbs.
  const float3 wo = chiDirFromAngles(0.5, 0.0);
  const RunningStats rough = reflectanceCc(makeCc(coatedMetal(glm::vec3(0.0f), glm::vec3(1.0f), 0.3f, 0.2f, 1e-5f, 200)),
                                           wo, 1, 100000, 4u);
  INFO("rough: " << rough.mean << " +- " << rough.standardError());
  CHECK(rough.mean <= 1.0 + 4.0 * rough.standardError());
  CHECK(rough.mean > 0.7);
  const RunningStats thick = reflectanceCc(makeCc(coatedMetal(glm::vec3(0.0f), glm::vec3(1.0f), 0.3f, 0.2f, 0.5f, 200)),
                                           wo, 1, 100000, 5u);
  CHECK(thick.mean < 0.5 * rough.mean);
}

TEST_CASE("coated_conductor: its walk is reciprocal in expectation" * doctest::test_suite("cpu")) {
  const Bsdf b = makeCc(coatedMetal(kGoldEta, kGoldK, 0.3f, 0.1f, 0.05f, 20));
  for (int pair = 0; pair < 6; ++pair) {
    const float4 u = rng_uniform4(7u, uint(pair), 0u, 0u);
    const float3 wa = chiDirFromAngles(std::acos(0.15 + 0.85 * u.x), 6.2832 * u.z);
    const float3 wb = chiDirFromAngles(std::acos(0.15 + 0.85 * u.y), 6.2832 * u.w);
    RunningStats ab, ba;
    for (std::uint32_t i = 0; i < 40000; ++i) {
      RngOut seed = pcg4d(i, uint(pair), 17u, 0u);
      ab.add(double(coated_conductor_walk(b.p.coated_conductor, wa, wb, seed, 1).y));
      seed = pcg4d(i, uint(pair), 23u, 0u);
      ba.add(double(coated_conductor_walk(b.p.coated_conductor, wb, wa, seed, 1).y));
    }
    const double se = std::sqrt(ab.standardError() * ab.standardError() + ba.standardError() * ba.standardError());
    INFO("pair " << pair << ": " << ab.mean << " vs " << ba.mean << " +- " << se);
    CHECK(std::fabs(ab.mean - ba.mean) < 4.0 * se);
    CHECK(ab.mean > 0.0);
  }
}

TEST_CASE("coated_conductor: the sampler passes chi-square against its pdf and fails a wrong one" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame();
  for (float alpha : {0.1f, 0.3f})
    for (double thetaO : {0.35, 1.1}) {
      const Bsdf b = makeCc(coatedMetal(kGoldEta, kGoldK, alpha, 0.2f, 0.01f));
      const Bsdf w = makeCc(coatedMetal(kGoldEta, kGoldK, alpha * 1.2f, 0.2f, 0.01f));
      const float3 wo = chiDirFromAngles(thetaO, 0.4);
      const montecl_test::SamplerChi2 r = montecl_test::samplerChi2(b, w, s, wo);
      const double stat = r.stat, wrong = r.wrong;
      const int dof = r.dof, dofWrong = r.dofWrong;
      INFO("base alpha " << alpha << " theta_o " << thetaO << ": chi2 " << stat << " dof " << dof << "; wrong " << wrong);
      CHECK(stat < chiSquareCritical(dof));
      CHECK(wrong > chiSquareCritical(dofWrong));
    }
}

}  // namespace test_file_bsdf_coated_conductor
