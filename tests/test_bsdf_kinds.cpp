// test_bsdf_kinds.cpp: the conductor, dielectric, thin_dielectric and metal_rough kinds
// (kernels/shared/bsdf_<kind>.h), compiled as C++: the exact Fresnel terms against closed forms,
// the conductor's Beckmann lobe (microfacet_beckmann.h) against its closed forms and its factor,
// chi-square tests of the rough lobes' samplers against their pdfs (failing against a wrong pdf),
// reciprocity of f, white furnaces (reflectance <= 1), and the delta lobes: eval and pdf 0, the
// mirror's weight F, the smooth dielectric from both sides (reflection picked with probability F,
// weights 1 and 1 / eta^2, Snell's law), the thin sheet's R' and straight-through transmission.
#include <doctest/doctest.h>

#include <cmath>

#include "bsdf_chi2.h"
#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "render/device_materials.h"
#include "stats.h"

namespace test_file_bsdf_kinds {  // keeps this file's helpers apart in a unity batch

using montecl::MaterialDesc;
using montecl_test::chiDirFromAngles;
using montecl_test::chiSquareCritical;
using montecl_test::chiSquareStat;
using montecl_test::RunningStats;

namespace {

Bsdf make(MaterialDesc d, float3 albedo = float3(1.0f)) { return bsdf_from_material(montecl::deviceMaterial(d), albedo); }

MaterialDesc conductorDesc(float alpha) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_conductor;
  d.eta = glm::vec3(0.143f, 0.375f, 1.442f);  // gold
  d.k = glm::vec3(3.983f, 2.386f, 1.603f);
  d.kindAlpha = alpha;
  return d;
}
MaterialDesc beckmannDesc(float alpha, glm::vec3 factor = glm::vec3(1.0f)) {
  MaterialDesc d = conductorDesc(alpha);
  d.beckmann = true;
  d.conductorFactor = factor;
  return d;
}
MaterialDesc metalRoughDesc(glm::vec3 base, float metallic, float roughness) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_metal_rough;
  d.albedo = base, d.metallic = metallic, d.roughness = roughness;
  return d;
}
// metal_rough (metallic 0) under a full clearcoat of roughness coatRoughness.
MaterialDesc coatedDesc(glm::vec3 base, float roughness, float coatRoughness) {
  MaterialDesc d = metalRoughDesc(base, 0.0f, roughness);
  d.clearcoat = 1.0f, d.clearcoatRoughness = coatRoughness;
  return d;
}
// metal_rough (metallic 0) under a sheen of colour c and roughness r.
MaterialDesc sheenDesc(glm::vec3 base, float roughness, glm::vec3 c, float r) {
  MaterialDesc d = metalRoughDesc(base, 0.0f, roughness);
  d.sheenColor = c, d.sheenRoughness = r;
  return d;
}
MaterialDesc iorDesc(std::uint32_t kind, float ior) {
  MaterialDesc d;
  d.kind = kind;
  d.ior = ior;
  return d;
}

}  // namespace

TEST_CASE("bsdf: exact Fresnel: the conductor with k = 0 is the dielectric; normal incidence closed forms" *
          doctest::test_suite("cpu")) {
  for (float eta : {1.2f, 1.5f, 2.4f})
    for (float c : {1.0f, 0.8f, 0.4f, 0.1f}) {
      float cosT;
      CHECK(fresnel_conductor1(c, eta, 0.0f) == doctest::Approx(fresnel_dielectric(c, eta, &cosT)).epsilon(1e-4));
    }
  const float n = 0.2f, k = 3.9f;
  CHECK(fresnel_conductor1(1.0f, n, k) ==
        doctest::Approx(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k)).epsilon(1e-5));
  float cosT;
  CHECK(fresnel_dielectric(1.0f, 1.5f, &cosT) == doctest::Approx(0.04f).epsilon(1e-5));
  CHECK(cosT == doctest::Approx(1.0f));
  CHECK(fresnel_dielectric(0.3f, 1.0f / 1.5f, &cosT) == 1.0f);  // total internal reflection
  CHECK(cosT == 0.0f);
  CHECK(fresnel_conductor1(0.0f, n, k) == doctest::Approx(1.0f));  // grazing: 1
}

TEST_CASE("bsdf: rough conductor and metal_rough samplers pass chi-square against their pdfs, fail a wrong one" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  struct Case {
    const char* what;
    MaterialDesc right, wrong;  // wrong: a plausible other normalised density
  };
  const Case cases[] = {
      {"conductor alpha 0.3", conductorDesc(0.3f), conductorDesc(0.36f)},
      {"conductor Beckmann alpha 0.3", beckmannDesc(0.3f), beckmannDesc(0.36f)},
      {"metal_rough dielectric r 0.5", metalRoughDesc(glm::vec3(0.6f, 0.5f, 0.4f), 0.0f, 0.5f),
       metalRoughDesc(glm::vec3(0.6f, 0.5f, 0.4f), 0.0f, 0.6f)},
      {"metal_rough metal r 0.4", metalRoughDesc(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.4f),
       metalRoughDesc(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.48f)},
      {"metal_rough clearcoat r 0.3 over red r 0.7", coatedDesc(glm::vec3(0.8f, 0.2f, 0.1f), 0.7f, 0.3f),
       coatedDesc(glm::vec3(0.8f, 0.2f, 0.1f), 0.7f, 0.36f)},
      {"metal_rough sheen r 0.5 over blue r 0.3", sheenDesc(glm::vec3(0.1f, 0.2f, 0.6f), 0.3f, glm::vec3(1.0f), 0.5f),
       sheenDesc(glm::vec3(0.1f, 0.2f, 0.6f), 0.3f, glm::vec3(0.3f), 0.5f)},
  };
  for (const Case& c : cases)
    for (double thetaO : {0.35, 1.1}) {
      const Bsdf b = make(c.right, float3(c.right.albedo.x, c.right.albedo.y, c.right.albedo.z));
      const Bsdf w = make(c.wrong, float3(c.wrong.albedo.x, c.wrong.albedo.y, c.wrong.albedo.z));
      const float3 wo = chiDirFromAngles(thetaO, 0.4);
      const montecl_test::SamplerChi2 r = montecl_test::samplerChi2(b, w, s, wo);
      const double stat = r.stat, wrong = r.wrong;
      const int dof = r.dof, dofWrong = r.dofWrong;
      INFO(c.what << " theta_o " << thetaO << ": chi2 " << stat << " dof " << dof << "; wrong " << wrong << " dof "
                  << dofWrong);
      CHECK(stat < chiSquareCritical(dof));
      CHECK(wrong > chiSquareCritical(dofWrong));
    }
}

TEST_CASE("bsdf: conductor and metal_rough are reciprocal; white furnaces reflect at most 1" * doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  MaterialDesc white = conductorDesc(0.5f);
  white.eta = glm::vec3(0.0f), white.k = glm::vec3(1.0f);  // F = 1 at every angle
  MaterialDesc whiteBeckmann = white;
  whiteBeckmann.beckmann = true;
  const MaterialDesc descs[] = {conductorDesc(0.2f), white, beckmannDesc(0.2f), whiteBeckmann, metalRoughDesc(glm::vec3(1.0f), 0.0f, 1.0f),
                                metalRoughDesc(glm::vec3(1.0f), 1.0f, 0.3f), metalRoughDesc(glm::vec3(1.0f), 0.5f, 0.7f)};
  for (const MaterialDesc& d : descs) {
    const Bsdf b = make(d);
    int asymmetric = 0;
    for (int i = 0; i < 2000; ++i) {
      const float4 u = rng_uniform4(5u, uint(i), 0u, 0u);
      const float3 a = chiDirFromAngles(std::acos(double(u.x)), 6.283 * u.y), c = chiDirFromAngles(std::acos(double(u.z)), 6.283 * u.w);
      const float3 fac = bsdf_f(b, s, a, c), fca = bsdf_f(b, s, c, a);
      for (int k = 0; k < 3; ++k) asymmetric += std::fabs(fac[k] - fca[k]) > 1e-4f * std::max(1.0f, std::fabs(fac[k]));
    }
    CHECK(asymmetric == 0);
    for (double thetaO : {0.0, 0.8, 1.45}) {
      const float3 wo = chiDirFromAngles(thetaO, 1.0);
      RunningStats r[3];
      for (int i = 0; i < 100000; ++i) {
        const float4 u = rng_uniform4(9u, uint(i), 1u, 0u);
        const BsdfSample bs = bsdf_sample(b, s, wo, u.x, u.y, u.z);
        for (int k = 0; k < 3; ++k) r[k].add(bs.pdf > 0.0f ? double(bs.weight[k]) : 0.0);
      }
      for (int k = 0; k < 3; ++k) {
        INFO("kind " << d.kind << " theta_o " << thetaO << ": reflectance " << r[k].mean << " +- " << r[k].standardError());
        CHECK(r[k].mean <= 1.0 + 4.0 * r[k].standardError());
        CHECK(r[k].mean > 0.3);  // and it reflects (a broken sampler absorbing everything fails)
      }
    }
  }
}

TEST_CASE("bsdf: Beckmann conductor: D normalised, Lambda within 0.35% of the erf form, f the closed form, "
          "sampled reflectance = the quadrature of f cos; the factor scales F" * doctest::test_suite("cpu")) {
  for (float alpha : {0.05f, 0.25f, 0.6f}) {  // integral of D cos over the hemisphere, z = cos theta
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double z = (i + 0.5) / n;
      sum += beckmann_d(chiDirFromAngles(std::acos(z), 0.0), alpha) * z * 2.0 * M_PI / n;
    }
    INFO("alpha " << alpha);
    CHECK(sum == doctest::Approx(1.0).epsilon(2e-3));
  }
  double worst = 0.0;  // G1 = 1 / (1 + Lambda) against the exact Lambda(a) = (erf(a) - 1) / 2 + e^-a^2 / (2 a sqrt(pi))
  for (double a = 0.05; a < 3.0; a += 0.01) {
    const double alpha = 0.3, theta = std::atan(1.0 / (a * alpha));
    const double exact = 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(M_PI));
    const double g1 = 1.0 / (1.0 + beckmann_lambda(chiDirFromAngles(theta, 0.7), float(alpha)));
    worst = std::max(worst, std::fabs(g1 * (1.0 + exact) - 1.0));
  }
  CHECK(worst < 0.0035);
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  const MaterialDesc d = beckmannDesc(0.25f);
  const Bsdf b = make(d);
  {  // f through the material record is F(wo.h) D G2 / (4 cos_o cos_i), in double
    const float3 wo = chiDirFromAngles(0.9, 0.2), wi = chiDirFromAngles(0.6, 2.9);
    const float3 h = normalize(wo + wi);
    const double D = std::exp(-(1.0 - h.z * h.z) / (h.z * h.z) / 0.0625) / (M_PI * 0.0625 * std::pow(double(h.z), 4));
    const double G2 = 1.0 / (1.0 + beckmann_lambda(wo, 0.25f) + beckmann_lambda(wi, 0.25f));
    const float3 f = bsdf_f(b, s, wo, wi);
    for (int k = 0; k < 3; ++k)
      CHECK(f[k] == doctest::Approx(fresnel_conductor1(dot(wo, h), d.eta[k], d.k[k]) * D * G2 / (4.0 * wo.z * wi.z)).epsilon(1e-4));
  }
  for (double thetaO : {0.3, 1.2}) {  // the sampler's mean weight is the reflectance f cos integrates to
    const float3 wo = chiDirFromAngles(thetaO, 0.5);
    RunningStats r;
    for (int i = 0; i < 200000; ++i) {
      const float4 u = rng_uniform4(31u, uint(i), 2u, 0u);
      const BsdfSample bs = bsdf_sample(b, s, wo, u.x, u.y, u.z);
      r.add(bs.pdf > 0.0f ? double(bs.weight.y) : 0.0);
    }
    double quad = 0.0;
    const int nz = 800, nphi = 800;
    for (int i = 0; i < nz; ++i)
      for (int j = 0; j < nphi; ++j) {
        const float3 wi = chiDirFromAngles(std::acos((i + 0.5) / nz), 2.0 * M_PI * (j + 0.5) / nphi);
        quad += double(bsdf_eval(b, s, wo, wi).y) * (2.0 * M_PI) / (double(nz) * nphi);
      }
    INFO("theta_o " << thetaO << ": sampled " << r.mean << " +- " << r.standardError() << ", quadrature " << quad);
    CHECK(std::fabs(r.mean - quad) < 4.0 * r.standardError() + 2e-3 * quad);
  }
  {  // the factor multiplies F: f, the sample weights (rough and mirror) and the albedo AOV
    const glm::vec3 factor(0.3f, 0.5f, 0.7f);
    const float3 wo = chiDirFromAngles(0.5, 0.1), wi = chiDirFromAngles(0.7, 3.0);
    for (bool rough : {true, false}) {
      MaterialDesc one = beckmannDesc(rough ? 0.25f : 0.0f), scaled = beckmannDesc(rough ? 0.25f : 0.0f, factor);
      const Bsdf b1 = make(one), b3 = make(scaled);
      const BsdfSample s1 = bsdf_sample(b1, s, wo, 0.3f, 0.6f, 0.5f), s3 = bsdf_sample(b3, s, wo, 0.3f, 0.6f, 0.5f);
      const float3 a1 = bsdf_albedo(b1), a3 = bsdf_albedo(b3);
      for (int k = 0; k < 3; ++k) {
        INFO("rough " << rough << " channel " << k);
        CHECK(s3.weight[k] == doctest::Approx(s1.weight[k] * factor[k]).epsilon(1e-6));
        CHECK(a3[k] == doctest::Approx(a1[k] * factor[k]).epsilon(1e-6));
        if (rough) CHECK(bsdf_f(b3, s, wo, wi)[k] == doctest::Approx(bsdf_f(b1, s, wo, wi)[k] * factor[k]).epsilon(1e-6));
      }
      CHECK(s1.weight.y > 0.0f);
    }
  }
}

TEST_CASE("bsdf: delta lobes: eval and pdf 0; mirror weight F; smooth dielectric both sides; thin sheet" *
          doctest::test_suite("cpu")) {
  const float3 wo = chiDirFromAngles(0.7, 0.3);
  const float cosO = wo.z;
  {  // the smooth conductor: the mirror direction, weight F(cos_o), flagged delta
    const MaterialDesc d = conductorDesc(0.0f);
    const Bsdf b = make(d);
    const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
    REQUIRE(bsdf_is_delta(b));
    const BsdfSample bs = bsdf_sample(b, s, wo, 0.3f, 0.6f, 0.5f);
    CHECK(bs.flags == MCL_BSDF_DELTA);
    CHECK(bs.pdf == 1.0f);
    CHECK(bs.wi.x == doctest::Approx(-wo.x));
    CHECK(bs.wi.z == doctest::Approx(wo.z));
    for (int k = 0; k < 3; ++k) CHECK(bs.weight[k] == doctest::Approx(fresnel_conductor1(cosO, d.eta[k], d.k[k])).epsilon(1e-6));
    CHECK(bsdf_pdf(b, s, wo, bs.wi) == 0.0f);
    CHECK(bsdf_eval(b, s, wo, bs.wi).x == 0.0f);
  }
  for (int backface : {0, 1}) {  // the smooth dielectric from outside (front) and from inside (back)
    const Bsdf b = make(iorDesc(MCL_MATERIAL_dielectric, 1.5f));
    const SurfaceFrame s = montecl_test::flatBsdfFrame(backface);
    const float eta = backface ? 1.0f / 1.5f : 1.5f;
    const float3 w = backface ? chiDirFromAngles(0.5, 0.3) : wo;  // inside: below the critical angle 0.73
    float cosT;
    const float F = fresnel_dielectric(w.z, eta, &cosT);
    const int n = 200000;
    int reflected = 0, bad = 0;
    for (int i = 0; i < n; ++i) {
      const float4 u = rng_uniform4(21u, uint(i), uint(backface), 0u);
      const BsdfSample bs = bsdf_sample(b, s, w, u.x, u.y, u.z);
      bad += !(bs.pdf > 0.0f) || !(bs.flags & MCL_BSDF_DELTA) || bsdf_pdf(b, s, w, bs.wi) != 0.0f;
      if (bs.wi.z > 0.0f) {
        ++reflected;
        bad += bs.weight.x != 1.0f || std::fabs(bs.pdf - F) > 1e-6f || std::fabs(bs.wi.z - w.z) > 1e-6f;
      } else {
        const float sinI = std::sqrt(1.0f - w.z * w.z), sinT = std::sqrt(1.0f - bs.wi.z * bs.wi.z);
        bad += std::fabs(bs.weight.x - 1.0f / (eta * eta)) > 1e-6f || std::fabs(bs.pdf - (1.0f - F)) > 1e-6f;
        bad += std::fabs(sinT * eta - sinI) > 1e-5f || !(bs.flags & MCL_BSDF_TRANSMISSION);  // Snell
      }
      const BsdfWeight dw = bsdf_direction_weight(b, s, w, bs.wi, 0.0f);
      bad += !dw.counts || dw.weight.x != bs.weight.x;
    }
    const double p = double(reflected) / n, se = std::sqrt(double(F) * (1.0 - F) / n);
    INFO("backface " << backface << ": reflected " << p << ", F " << F);
    CHECK(bad == 0);
    CHECK(std::fabs(p - F) < 4.0 * se);
  }
  {  // total internal reflection from inside past the critical angle: always reflected, weight 1
    const Bsdf b = make(iorDesc(MCL_MATERIAL_dielectric, 1.5f));
    const BsdfSample bs = bsdf_sample(b, montecl_test::flatBsdfFrame(1), chiDirFromAngles(1.0, 0.3), 0.5f, 0.5f, 0.999f);
    CHECK(bs.wi.z > 0.0f);
    CHECK(bs.weight.x == 1.0f);
  }
  {  // the thin sheet: R' = R + T^2 R / (1 - R^2); transmission straight through
    const Bsdf b = make(iorDesc(MCL_MATERIAL_thin_dielectric, 1.5f));
    float cosT;
    const float R = fresnel_dielectric(cosO, 1.5f, &cosT), T = 1.0f - R, R2 = R + T * T * R / (1.0f - R * R);
    const BsdfSample r = bsdf_sample(b, montecl_test::flatBsdfFrame(0), wo, 0.5f, 0.5f, R2 * 0.999f);
    const BsdfSample t = bsdf_sample(b, montecl_test::flatBsdfFrame(1), wo, 0.5f, 0.5f, R2 * 1.001f);
    CHECK(r.pdf == doctest::Approx(R2).epsilon(1e-6));
    CHECK(r.wi.z == doctest::Approx(wo.z));
    CHECK(t.pdf == doctest::Approx(1.0f - R2).epsilon(1e-5));
    CHECK(t.wi == -wo);
    CHECK(t.weight.x == 1.0f);
    CHECK(t.flags == (MCL_BSDF_DELTA | MCL_BSDF_TRANSMISSION));
  }
}

}  // namespace test_file_bsdf_kinds
