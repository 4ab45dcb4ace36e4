// test_bsdf.cpp: the diffuse kind's BSDF (kernels/shared/bsdf_diffuse.h, Lambert + GGX) and
// microfacet.h, compiled as C++: the GGX normal distribution is normalised, visible-normal sampling
// and the mixed Lambert + GGX sampling pass chi-square tests against their own pdfs (and fail
// against a wrong pdf), the sample weight is f cos / pdf, a white furnace of the BSDF alone
// reflects at most 1, the Ns -> alpha mapping, and the Lambert-only reduction (Ks = 0) is the plain
// Lambertian expressions; around a shading frame through the kind dispatch (shared/bsdf.h).
#include <doctest/doctest.h>

#include <functional>
#include <vector>

#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "bsdf_chi2.h"
#include "stats.h"

namespace test_file_bsdf {  // keeps this file's helpers apart in a unity batch

using montecl_test::chiSquareCritical;
using montecl_test::chiSquareStat;
using montecl_test::RunningStats;

namespace {

float3 dirFromAngles(double theta, double phi) {
  return float3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
}

const float3 kN(0.0f, 0.0f, 1.0f);

}  // namespace

TEST_CASE("GGX: D is normalised (integral of D cos over the hemisphere is 1), alpha from Ns" * doctest::test_suite("cpu")) {
  for (float alpha : {0.1f, 0.3f, 0.7f, 1.0f}) {
    const int n = 4000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {  // D depends on theta only; substitute z = cos theta
      double z = (i + 0.5) / n;
      sum += ggx_d(dirFromAngles(std::acos(z), 0.0), alpha) * z * 2.0 * M_PI / n;
    }
    INFO("alpha " << alpha);
    CHECK(sum == doctest::Approx(1.0).epsilon(2e-3));
  }
  CHECK(ggx_alpha_from_ns(0.0f) == doctest::Approx(1.0f));
  CHECK(ggx_alpha_from_ns(10.0f) == doctest::Approx(std::sqrt(2.0f / 12.0f)));
  CHECK(ggx_alpha_from_ns(1000.0f) == doctest::Approx(0.04468f).epsilon(1e-3));
  CHECK(ggx_alpha_from_ns(1e12f) == MCL_GGX_MIN_ALPHA);
}

TEST_CASE("GGX visible-normal sampling passes a chi-square test against its pdf, fails against a wrong one" * doctest::test_suite("cpu")) {
  for (float alpha : {0.25f, 0.6f}) {
    for (double thetaO : {0.3, 1.2}) {
      const float3 wo = dirFromAngles(thetaO, 0.4);
      const auto sample = [&](float4 u, float3& wi) {
        wi = reflect_about(wo, ggx_sample_visible_normal(wo, alpha, u.x, u.y));
        return wi.z > 0.0f;
      };
      int dof = 0;
      const double stat = chiSquareStat(sample, [&](float3 wi) { return ggx_pdf(wo, wi, alpha); }, 300000, dof);
      INFO("alpha " << alpha << " theta_o " << thetaO << ": chi2 " << stat << " dof " << dof);
      CHECK(stat < chiSquareCritical(dof));
      // A plausible wrong pdf: the same lobe 20% rougher (still a normalised density).
      int dofWrong = 0;
      const double wrong =
          chiSquareStat(sample, [&](float3 wi) { return ggx_pdf(wo, wi, alpha * 1.2f); }, 300000, dofWrong);
      INFO("wrong pdf: chi2 " << wrong << " dof " << dofWrong);
      CHECK(wrong > chiSquareCritical(dofWrong));
    }
  }
}

TEST_CASE("BSDF: Lambert + GGX mixture sampling passes a chi-square test against bsdf_pdf" * doctest::test_suite("cpu")) {
  const DiffuseBsdf b = diffuse_make(float3(0.3f, 0.4f, 0.2f), float3(0.5f), 0.35f);
  const float3 wo = dirFromAngles(0.8, 2.0);
  const auto sample = [&](float4 u, float3& wi) {
    BsdfSample s = diffuse_sample_about(b, kN, wo, u.x, u.y, u.z);
    wi = s.wi;
    return s.pdf > 0.0f;
  };
  int dof = 0;
  const double stat = chiSquareStat(sample, [&](float3 wi) { return diffuse_pdf_about(b, kN, wo, wi); }, 300000, dof);
  INFO("chi2 " << stat << " dof " << dof);
  CHECK(stat < chiSquareCritical(dof));
  const DiffuseBsdf lambert = diffuse_make(float3(0.3f, 0.4f, 0.2f), float3(0.0f), 0.35f);  // the wrong mixture
  int dofWrong = 0;
  const double wrong = chiSquareStat(sample, [&](float3 wi) { return diffuse_pdf_about(lambert, kN, wo, wi); }, 300000, dofWrong);
  CHECK(wrong > chiSquareCritical(dofWrong));
}

TEST_CASE("BSDF: sample weight is f cos / pdf, pdf matches bsdf_pdf, in a tilted frame" * doctest::test_suite("cpu")) {
  const DiffuseBsdf b = diffuse_make(float3(0.2f, 0.1f, 0.3f), float3(0.6f, 0.5f, 0.4f), 0.2f);
  const float3 n = normalize(float3(0.3f, -0.5f, 0.8f));
  const float3 wo = normalize(n + float3(0.5f, 0.2f, -0.1f));
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    float4 u = rng_uniform4(5u, uint(i), 0u, 0u);
    BsdfSample s = diffuse_sample_about(b, n, wo, u.x, u.y, u.z);
    if (!(s.pdf > 0.0f)) continue;
    ++checked;
    const float pdf = diffuse_pdf_about(b, n, wo, s.wi);
    const float3 w = diffuse_eval_about(b, n, wo, s.wi) / pdf;
    REQUIRE(s.pdf == doctest::Approx(pdf).epsilon(1e-3));
    for (int c = 0; c < 3; ++c) REQUIRE(s.weight[c] == doctest::Approx(w[c]).epsilon(1e-3));
  }
  CHECK(checked > 1500);
}

TEST_CASE("BSDF: white furnace of the BSDF alone: integral of f cos over the hemisphere <= 1" * doctest::test_suite("cpu")) {
  // Kd + Ks = 1 (the most a material may have after loading), several roughnesses and angles. The
  // integral is estimated two ways: importance sampled (mean of the weights) and uniformly.
  struct Case {
    float kd, ks, alpha;
  };
  for (Case c : {Case{0.0f, 1.0f, 0.05f}, Case{0.0f, 1.0f, 0.5f}, Case{0.0f, 1.0f, 1.0f}, Case{0.5f, 0.5f, 0.3f},
                 Case{1.0f, 0.0f, 0.3f}}) {
    const DiffuseBsdf b = diffuse_make(float3(c.kd), float3(c.ks), c.alpha);
    for (double thetaO : {0.0, 0.7, 1.45}) {
      const float3 wo = dirFromAngles(thetaO, 1.0);
      RunningStats sampled, uniform;
      for (int i = 0; i < 100000; ++i) {
        float4 u = rng_uniform4(9u, uint(i), 1u, 0u);
        BsdfSample s = diffuse_sample_about(b, kN, wo, u.x, u.y, u.z);
        sampled.add(s.pdf > 0.0f ? double(s.weight.x) : 0.0);
        float3 wi = sample_uniform_hemisphere(u.x, u.y);
        uniform.add(double(diffuse_eval_about(b, kN, wo, wi).x) / double(pdf_uniform_hemisphere()));
      }
      INFO("kd " << c.kd << " ks " << c.ks << " alpha " << c.alpha << " theta_o " << thetaO << ": sampled "
                 << sampled.mean << " +- " << sampled.standardError() << ", uniform " << uniform.mean << " +- "
                 << uniform.standardError());
      CHECK(sampled.mean <= 1.0 + 4.0 * sampled.standardError());
      CHECK(uniform.mean <= 1.0 + 4.0 * uniform.standardError());
      if (c.alpha >= 0.3f) {  // both estimate the same integral (uniform is too noisy for a sharp lobe)
        const double se = std::hypot(sampled.standardError(), uniform.standardError());
        CHECK(std::abs(sampled.mean - uniform.mean) < 4.0 * se + 1e-6);
      }
      if (c.ks == 0.0f) CHECK(sampled.mean == doctest::Approx(c.kd).epsilon(1e-6));  // Lambert: weight = Kd
      if (c.ks == 1.0f) CHECK(sampled.mean > 0.25);  // the lobe does reflect (not trivially <= 1)
      // alpha = 1 at normal incidence: D = 1/pi, G2 = 2 cos/(1 + cos), albedo = 1 - ln 2 exactly.
      if (c.ks == 1.0f && c.alpha == 1.0f && thetaO == 0.0)
        CHECK(std::abs(sampled.mean - (1.0 - std::log(2.0))) < 4.0 * sampled.standardError());
    }
  }
}

TEST_CASE("BSDF: with Ks = 0 the functions are the Lambertian expressions, bit for bit" * doctest::test_suite("cpu")) {
  const float3 kd(0.7f, 0.5f, 0.3f);
  const DiffuseBsdf b = diffuse_make(kd, float3(0.0f), 0.5f);
  CHECK(b.specProb == 0.0f);
  const float3 n = normalize(float3(0.1f, 0.9f, -0.2f));
  for (int i = 0; i < 100; ++i) {
    float4 u = rng_uniform4(1u, uint(i), 0u, 0u);
    BsdfSample s = diffuse_sample_about(b, n, n, u.x, u.y, u.z);
    const float3 local = sample_cosine_hemisphere(u.x, u.y);
    const float3 wi = to_world(local, n);
    REQUIRE(s.wi == wi);
    REQUIRE(s.weight == kd);
    REQUIRE(s.pdf == pdf_cosine_hemisphere(local.z));
    REQUIRE(diffuse_eval_about(b, n, n, wi) == kd * (dot(n, wi) * MCL_INV_PI));
    REQUIRE(diffuse_pdf_about(b, n, n, wi) == pdf_cosine_hemisphere(dot(n, wi)));
    REQUIRE(diffuse_f_about(b, n, n, wi) == kd * MCL_INV_PI);
  }
}

// --- the BSDF around a shading frame, through the kind dispatch (kernels/shared/bsdf.h) ----------
// ng = +z (the binning's hemisphere); ns tilted 35 degrees: Lambertian samples below ng are folded,
// glossy ones absorbed, and the pdf must say exactly that.

namespace {
Bsdf diffuseBsdf(float3 kd, float3 ks, float alpha) {
  Bsdf b;
  b.kind = MCL_MATERIAL_diffuse;
  b.p.diffuse = diffuse_make(kd, ks, alpha);
  return b;
}

SurfaceFrame tiltedFrame() {
  SurfaceFrame s;
  s.p = float3(0.0f);
  s.ng = kN;
  s.ns = dirFromAngles(35.0 * M_PI / 180.0, 0.0);
  s.smooth = 1;
  s.backface = 0;
  return s;
}
}  // namespace

TEST_CASE("Surface BSDF: with a tilted shading normal, sampling passes a chi-square test against its pdf (Lambert and Lambert + GGX), fails against the unfolded pdf" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame sf = tiltedFrame();
  const float3 wo = dirFromAngles(0.8, M_PI);  // 81 degrees from ns, on the side away from the tilt
  for (float ks : {0.0f, 0.5f}) {
    const Bsdf b = diffuseBsdf(float3(0.3f, 0.4f, 0.2f), float3(ks), 0.3f);
    const auto sample = [&](float4 u, float3& wi) {
      BsdfSample s = bsdf_sample(b, sf, wo, u.x, u.y, u.z);
      wi = s.wi;
      if (s.pdf > 0.0f) {  // every traced direction leaves above the geometric surface
        REQUIRE(wi.z > 0.0f);
        const float3 w = bsdf_eval(b, sf, wo, wi) / bsdf_pdf(b, sf, wo, wi);
        for (int c = 0; c < 3; ++c) REQUIRE(s.weight[c] == doctest::Approx(w[c]).epsilon(1e-3));
      }
      return s.pdf > 0.0f;
    };
    int dof = 0;
    const double stat = chiSquareStat(sample, [&](float3 wi) { return bsdf_pdf(b, sf, wo, wi); }, 300000, dof);
    INFO("Ks " << ks << ": chi2 " << stat << " dof " << dof);
    CHECK(stat < chiSquareCritical(dof));
    int dofWrong = 0;  // the plain lobe around ns, as if nothing were folded or absorbed
    const double wrong = chiSquareStat(sample, [&](float3 wi) { return diffuse_pdf_about(b.p.diffuse, sf.ns, wo, wi); }, 300000, dofWrong);
    INFO("unfolded pdf: chi2 " << wrong);
    CHECK(wrong > chiSquareCritical(dofWrong));
  }
}

TEST_CASE("Surface BSDF: directions below the geometric surface get f = 0 and pdf = 0; flat frames are bsdf.h's" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame sf = tiltedFrame();
  const Bsdf b = diffuseBsdf(float3(0.3f), float3(0.4f), 0.2f);
  const float3 wo = dirFromAngles(0.5, 0.3);
  const float3 below = normalize(float3(0.9f, 0.0f, -0.05f));  // above ns's plane, below ng's
  REQUIRE(dot(sf.ns, below) > 0.0f);
  CHECK(bsdf_pdf(b, sf, wo, below) == 0.0f);
  CHECK(bsdf_eval(b, sf, wo, below).x == 0.0f);
  CHECK(bsdf_f(b, sf, wo, below).x == 0.0f);
  SurfaceFrame flat = sf;
  flat.smooth = 0;
  flat.ns = flat.ng;
  const float3 wi = dirFromAngles(0.7, 2.0);
  CHECK(bsdf_pdf(b, flat, wo, wi) == diffuse_pdf_about(b.p.diffuse, kN, wo, wi));
  CHECK(bsdf_eval(b, flat, wo, wi).y == diffuse_eval_about(b.p.diffuse, kN, wo, wi).y);
  for (int i = 0; i < 100; ++i) {
    float4 u = rng_uniform4(9u, uint(i), 0u, 0u);
    BsdfSample s1 = bsdf_sample(b, flat, wo, u.x, u.y, u.z), s2 = diffuse_sample_about(b.p.diffuse, kN, wo, u.x, u.y, u.z);
    REQUIRE(s1.pdf == s2.pdf);
    REQUIRE(s1.wi.x == s2.wi.x);
  }
}

}  // namespace test_file_bsdf
