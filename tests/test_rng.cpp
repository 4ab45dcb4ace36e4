// test_rng.cpp: the counter-based generator of kernels/shared/rng.h: a pure function of its
// inputs, uniform (chi-square), in [0, 1), and uncorrelated across pixels, samples and groups.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "kernels/shared/rng.h"
#include "stats.h"

namespace test_file_rng {  // keeps this file's helpers apart in a unity batch

TEST_CASE("rng is a pure function of (seed, pixel, sample, group)" * doctest::test_suite("cpu")) {
  for (uint i = 0; i < 1000; ++i) {
    float4 a = rng_uniform4(5u, i, i * 7u, 2u);
    float4 b = rng_uniform4(5u, i, i * 7u, 2u);
    CHECK(a == b);
  }
}

TEST_CASE("pcg4d is injective on a grid of inputs" * doctest::test_suite("cpu")) {
  std::set<std::tuple<uint, uint, uint, uint>> seen;
  for (uint p = 0; p < 64; ++p)
    for (uint s = 0; s < 64; ++s)
      for (uint g = 0; g < 4; ++g)
        for (uint seed = 0; seed < 4; ++seed) {
          RngOut r = pcg4d(p, s, g, seed);
          seen.insert({r.x, r.y, r.z, r.w});
        }
  CHECK(seen.size() == 64u * 64u * 4u * 4u);
}

TEST_CASE("rng numbers are uniform on the unit interval in every component" * doctest::test_suite("cpu")) {
  const int bins = 64, n = 200000;
  std::vector<std::vector<double>> counts(4, std::vector<double>(bins, 0.0));
  for (int i = 0; i < n; ++i) {
    float4 u = rng_uniform4(0u, uint(i % 1000), uint(i / 1000), 1u);
    for (int c = 0; c < 4; ++c) {
      REQUIRE(u[c] >= 0.0f);
      REQUIRE(u[c] < 1.0f);
      counts[c][std::min(bins - 1, int(u[c] * bins))] += 1.0;
    }
  }
  for (int c = 0; c < 4; ++c) {
    double chi2 = 0.0, expected = double(n) / bins;
    for (double o : counts[c]) chi2 += (o - expected) * (o - expected) / expected;
    INFO("component " << c << " chi2 " << chi2);
    CHECK(chi2 < montecl_test::chiSquareCritical(bins - 1));
  }
}

TEST_CASE("neighbouring pixels, samples, groups and seeds are uncorrelated" * doctest::test_suite("cpu")) {
  // Pearson correlation of u(x) with u(x + 1) along each input; |r| must be small (n = 1e5).
  const int n = 100000;
  for (int axis = 0; axis < 4; ++axis) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < n; ++i) {
      uint in[4] = {uint(i), uint(i) * 3u, 1u, 9u};
      float a = rng_uniform4(in[3], in[0], in[1], in[2]).x;
      in[axis] += 1u;
      float b = rng_uniform4(in[3], in[0], in[1], in[2]).x;
      sx += a; sy += b; sxx += a * a; syy += b * b; sxy += a * b;
    }
    double cov = sxy / n - sx / n * sy / n;
    double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
    INFO("axis " << axis << " r = " << r);
    CHECK(std::fabs(r) < 4.0 / std::sqrt(double(n)));
  }
}

TEST_CASE("the dimension groups the stages use are uncorrelated with each other within a pixel" * doctest::test_suite("cpu")) {
  // Groups differing only in their high bits (camera 0 vs path 0x80000000) once gave a pixel's
  // jitter and its first BSDF direction a correlation of 0.6: edge pixels of the path-traced
  // Cornell box were biased (z up to 8 against Mitsuba 3). Pearson r of every component pair of
  // every pair of groups over 16 pixels x 4096 samples; |r| must stay below 5 / sqrt(n).
  const uint groups[] = {MCL_DIM_CAMERA, MCL_DIM_AO, MCL_DIM_LIGHT, MCL_DIM_LENS,
                         MCL_DIM_PATH, MCL_DIM_PATH + 1u, MCL_DIM_PATH + MCL_DIM_PATH_STRIDE,
                         MCL_DIM_PATH + MCL_DIM_PATH_STRIDE + 1u, MCL_DIM_PATH + 2u * MCL_DIM_PATH_STRIDE};
  const int ng = int(sizeof(groups) / sizeof(groups[0])), n = 16 * 4096;
  std::vector<std::vector<float>> u(size_t(ng) * 4, std::vector<float>(size_t(n)));
  for (int g = 0; g < ng; ++g)
    for (int i = 0; i < n; ++i) {
      float4 v = rng_uniform4(0u, 30u * 64u + 19u + uint(i / 4096) * 97u, uint(i % 4096), groups[g]);
      for (int c = 0; c < 4; ++c) u[size_t(g) * 4 + size_t(c)][size_t(i)] = v[c];
    }
  double worst = 0.0;
  for (size_t a = 0; a < u.size(); ++a)
    for (size_t b = (a / 4 + 1) * 4; b < u.size(); ++b) {
      double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (int i = 0; i < n; ++i) {
        double x = u[a][size_t(i)], y = u[b][size_t(i)];
        sx += x; sy += y; sxx += x * x; syy += y * y; sxy += x * y;
      }
      double cov = sxy / n - sx / n * sy / n;
      double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
      INFO("groups " << groups[a / 4] << "." << a % 4 << " and " << groups[b / 4] << "." << b % 4 << ": r = " << r);
      CHECK(std::fabs(r) < 5.0 / std::sqrt(double(n)));
      worst = std::max(worst, std::fabs(r));
    }
  MESSAGE("largest |r| " << worst << " (limit " << 5.0 / std::sqrt(double(n)) << ")");
}

}  // namespace test_file_rng
