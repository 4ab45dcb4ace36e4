// test_bsdf_rough_dielectric.cpp: the rough dielectric (kernels/shared/bsdf_dielectric.h, alpha > 0:
// GGX reflection and transmission, Walter et al. 2007), compiled as C++: its sampler passes a
// chi-square test against its pdf over the whole sphere of directions (reflected and transmitted,
// several alpha and ior, from outside and from inside) and fails against a wrong ior; the pdf
// integrates to the sampler's non-absorbed fraction (<= 1); eval obeys the adjoint relation
// f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2 (the radiance scaling 1 / eta^2 swapped); as alpha -> 0 the
// reflected and transmitted energies are the smooth dielectric's Fresnel split F, (1 - F) / eta^2;
// the albedo AOV is the sampler's mean energy at normal incidence.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "bsdf_chi2.h"
#include "stats.h"

namespace test_file_bsdf_rough_dielectric {  // keeps this file's helpers apart in a unity batch

using montecl_test::chiDirFromAngles;
using montecl_test::chiSquareCritical;
using montecl_test::RunningStats;

namespace {

// Chi-square of sampled directions binned over the whole sphere in (cos theta in [-1, 1], phi)
// against pdf integrated over each bin (midpoint rule on a sub-grid), plus an "absorbed" bin of
// mass 1 - integral. Bins expecting < 5 samples are pooled. *integral receives the pdf's integral.
double sphereChiSquare(const std::function<bool(float4, float3&)>& sample, const std::function<double(float3)>& pdf,
                       int count, int& dof, double* integral) {
  const int nz = 40, nphi = 24, sub = 10;
  std::vector<double> observed(nz * nphi + 1, 0.0), expected(nz * nphi + 1, 0.0);
  for (int i = 0; i < count; ++i) {
    float3 wi;
    if (!sample(rng_uniform4(29u, uint(i), 5u, 0u), wi)) {
      observed[nz * nphi] += 1.0;
      continue;
    }
    double phi = std::atan2(wi.y, wi.x);
    if (phi < 0) phi += 2.0 * M_PI;
    const int bz = std::min(nz - 1, std::max(0, int((wi.z + 1.0) * 0.5 * nz)));
    const int bp = std::min(nphi - 1, int(phi / (2.0 * M_PI) * nphi));
    observed[bz * nphi + bp] += 1.0;
  }
  double total = 0.0;
  for (int bz = 0; bz < nz; ++bz)
    for (int bp = 0; bp < nphi; ++bp) {
      double sum = 0.0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double z = -1.0 + 2.0 * (bz + (a + 0.5) / sub) / nz, phi = 2.0 * M_PI * (bp + (b + 0.5) / sub) / nphi;
          sum += pdf(chiDirFromAngles(std::acos(z), phi));
        }
      const double p = sum / (sub * sub) * (2.0 / nz) * (2.0 * M_PI / nphi);
      expected[bz * nphi + bp] = p * count;
      total += p;
    }
  *integral = total;
  expected[nz * nphi] = std::max(0.0, 1.0 - total) * count;
  double stat = 0.0, poolObs = 0.0, poolExp = 0.0;
  dof = -1;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    if (expected[k] < 5.0) {
      poolObs += observed[k];
      poolExp += expected[k];
      continue;
    }
    const double d = observed[k] - expected[k];
    stat += d * d / expected[k];
    ++dof;
  }
  if (poolExp > 0.0) {
    const double d = poolObs - poolExp;
    stat += d * d / std::max(poolExp, 5.0);
    ++dof;
  }
  return stat;
}

}  // namespace

TEST_CASE("rough dielectric: sampling passes a whole-sphere chi-square test against its pdf, fails a wrong ior; "
          "the pdf integrates to the non-absorbed fraction" *
          doctest::test_suite("cpu")) {
  const int n = 200000;
  for (float alpha : {0.15f, 0.5f}) {
    for (float ior : {1.5f, 1.33f}) {
      for (int backface : {0, 1}) {
        for (double thetaO : {0.4, 1.2}) {
          const SurfaceFrame sf = montecl_test::flatBsdfFrame(backface);
          const DielectricBsdf b = dielectric_make(ior, alpha);
          const float3 wo = chiDirFromAngles(thetaO, 0.7);
          int absorbed = 0, transmitted = 0;
          const auto sample = [&](float4 u, float3& wi) {
            const BsdfSample s = dielectric_sample(b, sf, wo, u.x, u.y, u.z);
            wi = s.wi;
            return s.pdf > 0.0f;
          };
          for (int i = 0; i < n; ++i) {
            const float4 u = rng_uniform4(29u, uint(i), 5u, 0u);
            const BsdfSample s = dielectric_sample(b, sf, wo, u.x, u.y, u.z);
            absorbed += !(s.pdf > 0.0f);
            transmitted += s.pdf > 0.0f && (s.flags & MCL_BSDF_TRANSMISSION) != 0 && s.wi.z < 0.0f;
          }
          int dof = 0;
          double integral = 0.0;
          const double stat =
              sphereChiSquare(sample, [&](float3 wi) { return dielectric_pdf(b, sf, wo, wi); }, n, dof, &integral);
          INFO("alpha " << alpha << " ior " << ior << std::string(backface ? " from inside" : " from outside") << " theta_o "
                        << thetaO << ": chi2 " << stat << " dof " << dof << ", pdf integral " << integral
                        << ", absorbed " << absorbed << ", transmitted " << transmitted);
          CHECK(stat < chiSquareCritical(dof));
          if (!backface) CHECK(transmitted > n / 2);  // from outside, most of it is refracted
          CHECK(transmitted > n / 100);               // both hemispheres take part
          CHECK(integral <= 1.0 + 5e-3);
          CHECK(std::fabs(integral - (1.0 - double(absorbed) / n)) < 1e-2);
          // The same sampler against the pdf of a 10% higher ior (the transmitted lobe moves).
          const DielectricBsdf wrongB = dielectric_make(ior * 1.1f, alpha);
          int dofWrong = 0;
          double wrongIntegral = 0.0;
          const double wrong = sphereChiSquare(
              sample, [&](float3 wi) { return dielectric_pdf(wrongB, sf, wo, wi); }, n, dofWrong, &wrongIntegral);
          INFO("wrong ior: chi2 " << wrong << " dof " << dofWrong);
          CHECK(wrong > chiSquareCritical(dofWrong));
        }
      }
    }
  }
}

TEST_CASE("rough dielectric: eval obeys the adjoint relation f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2" *
          doctest::test_suite("cpu")) {
  for (float alpha : {0.1f, 0.4f, 0.9f}) {
    for (float ior : {1.5f, 1.33f, 2.4f}) {
      const DielectricBsdf b = dielectric_make(ior, alpha);
      int checked = 0, transmissions = 0, bad = 0;
      for (int i = 0; i < 20000; ++i) {
        const float4 u = rng_uniform4(41u, uint(i), 0u, 0u);
        const int backface = u.w < 0.5f;
        const SurfaceFrame a = montecl_test::flatBsdfFrame(backface);
        const float3 wo = chiDirFromAngles(std::acos(0.02 + 0.98 * u.x), 2.0 * M_PI * u.y);
        const float zi = -1.0f + 2.0f * u.z;  // wi anywhere on the sphere
        const float4 v = rng_uniform4(41u, uint(i), 1u, 0u);
        const float3 wi = chiDirFromAngles(std::acos(zi), 2.0 * M_PI * v.x);
        if (std::fabs(zi) < 0.02f) continue;
        const int transmit = wi.z < 0.0f;
        // The reverse query comes from wi's side: that side's frame (ng, ns toward wi) and medium.
        SurfaceFrame r = a;
        if (transmit) {
          r.ng = r.ns = float3(0.0f, 0.0f, -1.0f);
          r.backface = !backface;
        }
        const double nO = backface ? ior : 1.0, nI = transmit ? (backface ? 1.0 : ior) : nO;
        const double fwd = double(dielectric_eval(b, a, wo, wi).x) / std::fabs(wi.z) / (nO * nO);
        const double rev = double(dielectric_eval(b, r, wi, wo).x) / std::fabs(wo.z) / (nI * nI);
        // Far below the lobes' peaks (near total internal reflection, where 1 - F cancels) float
        // rounding reaches ~0.5%: the relation is checked where either side has a density.
        if (!(fwd > 1e-3 || rev > 1e-3)) continue;
        ++checked;
        transmissions += transmit;
        const bool ok = std::fabs(fwd - rev) <= 1e-2 * std::max(fwd, rev);  // eta^2 is 1.8 .. 5.8
        if (!ok && bad < 5)
          MESSAGE("backface " << backface << " wo " << wo.x << " " << wo.y << " " << wo.z << " wi " << wi.x << " " << wi.y
                              << " " << wi.z << ": " << fwd << " vs " << rev);
        bad += !ok;
      }
      INFO("alpha " << alpha << " ior " << ior << ": " << checked << " pairs, " << transmissions << " transmitted");
      CHECK(checked > 3000);
      CHECK(transmissions > 1000);
      CHECK(bad == 0);
    }
  }
}

TEST_CASE("rough dielectric: as alpha goes to 0 the reflected and transmitted energies are the smooth Fresnel split" *
          doctest::test_suite("cpu")) {
  const int n = 40000;
  for (float ior : {1.5f, 1.33f}) {
    for (int backface : {0, 1}) {
      for (double thetaO : {0.2, 0.7, 1.2}) {
        const SurfaceFrame sf = montecl_test::flatBsdfFrame(backface);
        const DielectricBsdf rough = dielectric_make(ior, 1e-3f), smooth = dielectric_make(ior, 0.0f);
        const float3 wo = chiDirFromAngles(thetaO, 1.1);
        RunningStats rr, rt, sr, st;  // reflected / transmitted weight, rough and smooth
        for (int i = 0; i < n; ++i) {
          const float4 u = rng_uniform4(53u, uint(i), 0u, 0u);
          const BsdfSample r = dielectric_sample(rough, sf, wo, u.x, u.y, u.z);
          const BsdfSample s = dielectric_sample(smooth, sf, wo, u.x, u.y, u.z);
          rr.add(r.pdf > 0.0f && r.wi.z > 0.0f ? double(r.weight.x) : 0.0);
          rt.add(r.pdf > 0.0f && r.wi.z < 0.0f ? double(r.weight.x) : 0.0);
          sr.add(s.pdf > 0.0f && s.wi.z > 0.0f ? double(s.weight.x) : 0.0);
          st.add(s.pdf > 0.0f && s.wi.z < 0.0f ? double(s.weight.x) : 0.0);
        }
        const double eta = backface ? 1.0 / ior : ior;
        float cosT;
        const double F = fresnel_dielectric(float(std::cos(thetaO)), float(eta), &cosT);
        INFO("ior " << ior << std::string(backface ? " from inside" : " from outside") << " theta_o " << thetaO << ": F " << F
                    << "; rough R " << rr.mean << " +- " << rr.standardError() << " T " << rt.mean << " +- "
                    << rt.standardError() << "; smooth R " << sr.mean << " T " << st.mean);
        // The smooth kind's estimate, and the closed form F and (1 - F) / eta^2.
        CHECK(std::fabs(rr.mean - F) <= 4.0 * rr.standardError() + 2e-3);
        CHECK(std::fabs(rt.mean - (1.0 - F) / (eta * eta)) <= 4.0 * rt.standardError() + 2e-3);
        CHECK(std::fabs(rr.mean - sr.mean) <= 4.0 * std::hypot(rr.standardError(), sr.standardError()) + 2e-3);
        CHECK(std::fabs(rt.mean - st.mean) <= 4.0 * std::hypot(rt.standardError(), st.standardError()) + 2e-3);
      }
    }
  }
}

TEST_CASE("rough dielectric: alpha 0 stays the smooth delta kind; a positive alpha is not delta and is sampled into "
          "both sides with its flags" *
          doctest::test_suite("cpu")) {
  const SurfaceFrame sf = montecl_test::flatBsdfFrame(0);
  const float3 wo = chiDirFromAngles(0.5, 0.3);
  const DielectricBsdf smooth = dielectric_make(1.5f, 0.0f), rough = dielectric_make(1.5f, 0.3f);
  CHECK(dielectric_is_delta(smooth));
  CHECK_FALSE(dielectric_is_delta(rough));
  int refl = 0, trans = 0;
  for (int i = 0; i < 1000; ++i) {
    const float4 u = rng_uniform4(7u, uint(i), 0u, 0u);
    const BsdfSample s = dielectric_sample(smooth, sf, wo, u.x, u.y, u.z);
    REQUIRE((s.flags & MCL_BSDF_DELTA) != 0);
    CHECK(dielectric_pdf(smooth, sf, wo, s.wi) == 0.0f);
    CHECK(dielectric_eval(smooth, sf, wo, s.wi).x == 0.0f);
    const BsdfSample r = dielectric_sample(rough, sf, wo, u.x, u.y, u.z);
    if (!(r.pdf > 0.0f)) continue;
    CHECK((r.flags & MCL_BSDF_DELTA) == 0);
    CHECK(((r.flags & MCL_BSDF_TRANSMISSION) != 0) == (r.wi.z < 0.0f));
    refl += r.wi.z > 0.0f;
    trans += r.wi.z < 0.0f;
  }
  CHECK(refl > 10);
  CHECK(trans > 500);
}

// The albedo AOV of the rough dielectric is its directional albedo at normal incidence from
// outside, in energy (reflected + transmitted): the mean of its sample weights there, each
// transmission's times eta^2 (undoing the radiance scaling). The kind computes it by a 32-point
// quadrature; here the sampler's Monte Carlo mean checks it (z-test, plus 5e-4 for the quadrature).
TEST_CASE("rough dielectric: the albedo AOV is the directional albedo at normal incidence" * doctest::test_suite("cpu")) {
  const SurfaceFrame s = montecl_test::flatBsdfFrame(0);
  const float3 wo(0.0f, 0.0f, 1.0f);
  const int n = 400000;
  for (float ior : {1.5f, 2.4f})
    for (float alpha : {0.01f, 0.3f, 0.7f, 1.0f}) {
      const DielectricBsdf b = dielectric_make(ior, alpha);
      const float albedo = dielectric_albedo(b).x;
      RunningStats e;
      for (int i = 0; i < n; ++i) {
        const float4 u = rng_uniform4(23u, uint(i), 0u, 0u);
        const BsdfSample bs = dielectric_sample(b, s, wo, u.x, u.y, u.z);
        const bool t = (bs.flags & MCL_BSDF_TRANSMISSION) != 0;
        e.add(bs.pdf > 0.0f ? double(bs.weight.x) * (t ? double(ior) * ior : 1.0) : 0.0);
      }
      INFO("ior " << ior << ", alpha " << alpha << ": albedo " << albedo << ", sampled " << e.mean << " +- " << e.standardError());
      CHECK(std::fabs(e.mean - albedo) < 4.0 * e.standardError() + 5e-4);
      CHECK(albedo <= 1.0f);
    }
  CHECK(dielectric_albedo(dielectric_make(1.5f, 0.0f)).x == 1.0f);  // smooth: all of it
}

}  // namespace test_file_bsdf_rough_dielectric
