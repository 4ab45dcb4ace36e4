// test_sampling.cpp: the hemisphere warps of kernels/shared/sampling.h, compiled as C++: pdfs
// integrate to one, chi-square tests of samples against their pdfs, orthonormal frames.
#include <doctest/doctest.h>

#include <functional>
#include <vector>

#include "kernels/shared/rng.h"
#include "kernels/shared/sampling.h"
#include "stats.h"

namespace test_file_sampling {  // keeps this file's helpers apart in a unity batch

using montecl_test::chiSquareCritical;

namespace {

// Integral over the sphere of pdf(cos theta), midpoint rule in (cos theta, phi).
double integrateOverSphere(const std::function<double(double)>& pdfOfCos) {
  const int n = 4000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    double z = -1.0 + (i + 0.5) * 2.0 / n;
    sum += pdfOfCos(z) * (2.0 / n) * 2.0 * M_PI;  // dw = dz dphi, pdf independent of phi
  }
  return sum;
}

// Chi-square statistic of `count` samples binned in (z, phi) against the expected probability of
// each bin; returns the statistic and the degrees of freedom.
struct ChiSquare {
  double statistic = 0.0;
  int dof = 0;
};
ChiSquare chiSquareHemisphere(const std::function<float3(float, float)>& warp,
                              const std::function<double(double, double)>& probZRange, int count) {
  const int nz = 16, nphi = 32;
  std::vector<double> observed(nz * nphi, 0.0);
  for (int i = 0; i < count; ++i) {
    float4 u = rng_uniform4(7u, uint(i), 0u, 0u);
    float3 d = warp(u.x, u.y);
    REQUIRE(d.z >= 0.0f);
    double phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2.0 * M_PI;
    int bz = std::min(nz - 1, int(d.z * nz));
    int bp = std::min(nphi - 1, int(phi / (2.0 * M_PI) * nphi));
    observed[bz * nphi + bp] += 1.0;
  }
  ChiSquare cs;
  for (int bz = 0; bz < nz; ++bz) {
    double pz = probZRange(double(bz) / nz, double(bz + 1) / nz) / nphi;
    for (int bp = 0; bp < nphi; ++bp) {
      double expected = pz * count;
      double d = observed[bz * nphi + bp] - expected;
      cs.statistic += d * d / expected;
    }
  }
  cs.dof = nz * nphi - 1;
  return cs;
}

}  // namespace

TEST_CASE("hemisphere pdfs integrate to one over the sphere" * doctest::test_suite("cpu")) {
  CHECK(integrateOverSphere([](double z) { return z >= 0 ? double(pdf_uniform_hemisphere()) : 0.0; }) ==
        doctest::Approx(1.0).epsilon(1e-6));
  CHECK(integrateOverSphere([](double z) { return double(pdf_cosine_hemisphere(float(z))); }) ==
        doctest::Approx(1.0).epsilon(1e-4));
}

TEST_CASE("uniform hemisphere samples pass a chi-square test against p = 1/(2 pi)" * doctest::test_suite("cpu")) {
  ChiSquare cs = chiSquareHemisphere(sample_uniform_hemisphere, [](double a, double b) { return b - a; }, 400000);
  INFO("chi2 = " << cs.statistic << " dof = " << cs.dof);
  CHECK(cs.statistic < chiSquareCritical(cs.dof));
  // The same samples judged against the cosine pdf must fail: the test has power.
  ChiSquare wrong = chiSquareHemisphere(sample_uniform_hemisphere, [](double a, double b) { return b * b - a * a; }, 400000);
  CHECK(wrong.statistic > chiSquareCritical(wrong.dof));
}

TEST_CASE("cosine hemisphere samples pass a chi-square test against p = cos/pi" * doctest::test_suite("cpu")) {
  ChiSquare cs = chiSquareHemisphere(sample_cosine_hemisphere, [](double a, double b) { return b * b - a * a; }, 400000);
  INFO("chi2 = " << cs.statistic << " dof = " << cs.dof);
  CHECK(cs.statistic < chiSquareCritical(cs.dof));
  ChiSquare wrong = chiSquareHemisphere(sample_cosine_hemisphere, [](double a, double b) { return b - a; }, 400000);
  CHECK(wrong.statistic > chiSquareCritical(wrong.dof));
}

TEST_CASE("warped directions are unit vectors" * doctest::test_suite("cpu")) {
  for (int i = 0; i < 10000; ++i) {
    float4 u = rng_uniform4(1u, uint(i), 2u, 3u);
    CHECK(glm::length(sample_uniform_hemisphere(u.x, u.y)) == doctest::Approx(1.0f).epsilon(1e-5));
    CHECK(glm::length(sample_cosine_hemisphere(u.z, u.w)) == doctest::Approx(1.0f).epsilon(1e-5));
  }
}

TEST_CASE("make_basis gives a right-handed orthonormal frame, also at the poles" * doctest::test_suite("cpu")) {
  std::vector<float3> normals = {float3(0, 0, 1), float3(0, 0, -1), float3(1, 0, 0), float3(0, -1, 0)};
  for (int i = 0; i < 1000; ++i) {
    float4 u = rng_uniform4(3u, uint(i), 0u, 0u);
    normals.push_back(normalize(float3(u.x - 0.5f, u.y - 0.5f, u.z - 0.5f)));
  }
  for (float3 n : normals) {
    float3 t, b;
    make_basis(n, &t, &b);
    CHECK(glm::length(t) == doctest::Approx(1.0f).epsilon(1e-5));
    CHECK(glm::length(b) == doctest::Approx(1.0f).epsilon(1e-5));
    CHECK(std::fabs(dot(t, b)) < 1e-5f);
    CHECK(std::fabs(dot(t, n)) < 1e-5f);
    CHECK(std::fabs(dot(b, n)) < 1e-5f);
    CHECK(dot(cross(t, b), n) == doctest::Approx(1.0f).epsilon(1e-5));
  }
}

TEST_CASE("concentric disk samples are uniform: lifted to the hemisphere (Malley) they pass the cosine test" * doctest::test_suite("cpu")) {
  const auto lifted = [](float u1, float u2) {
    float2 p = sample_concentric_disk(u1, u2);
    REQUIRE(p.x * p.x + p.y * p.y <= 1.0f + 1e-6f);
    return make_float3(p.x, p.y, std::sqrt(std::max(0.0f, 1.0f - p.x * p.x - p.y * p.y)));
  };
  ChiSquare cs = chiSquareHemisphere(lifted, [](double a, double b) { return b * b - a * a; }, 400000);
  CHECK(cs.statistic < chiSquareCritical(cs.dof));
  ChiSquare wrong = chiSquareHemisphere(lifted, [](double a, double b) { return b - a; }, 400000);
  CHECK(wrong.statistic > chiSquareCritical(wrong.dof));
  // The polynomial sin/cos the map uses (the same operations on every device) match libm.
  for (int i = 0; i <= 1000; ++i) {
    const float x = -float(M_PI / 4) + float(M_PI / 2) * float(i) / 1000.0f;
    float sn, cs;
    mcl_sincos_poly(x, &sn, &cs);
    CHECK(std::fabs(sn - std::sin(x)) < 2e-7f);
    CHECK(std::fabs(cs - std::cos(x)) < 2e-7f);
  }
}

TEST_CASE("portable cosine hemisphere (polynomial sin/cos) passes the chi-square test; mcl_sincos_turns matches libm" * doctest::test_suite("cpu")) {
  ChiSquare cs = chiSquareHemisphere(sample_cosine_hemisphere, [](double a, double b) { return b * b - a * a; }, 400000);
  CHECK(cs.statistic < chiSquareCritical(cs.dof));
  ChiSquare wrong = chiSquareHemisphere(sample_cosine_hemisphere, [](double a, double b) { return b - a; }, 400000);
  CHECK(wrong.statistic > chiSquareCritical(wrong.dof));
  double worst = 0.0;
  for (int i = 0; i < 4096; ++i) {
    const float u = float(i) / 4096.0f;
    float s, c;
    mcl_sincos_turns(u, &s, &c);
    worst = std::max({worst, std::fabs(double(c) - std::cos(2.0 * M_PI * u)), std::fabs(double(s) - std::sin(2.0 * M_PI * u))});
  }
  CHECK(worst < 5e-7);
}

}  // namespace test_file_sampling
