// test_emitter_guide.cpp: the emitter pick's guide table (host/render/emitter_guide.cpp,
// kernels/shared/lights.h pick_emitter): the guided search returns what a search of the whole cdf
// returns, for random tables (runs of equal cdf values among them) and for the u where buckets and
// cdf steps change, one ulp either side, and out-of-range and NaN numbers.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "kernels/shared/lights.h"
#include "render/emitter_guide.h"

namespace test_file_emitter_guide {  // keeps this file's helpers apart in a unity batch

using namespace montecl;

namespace {

uint wholeSearch(const std::vector<Emitter>& e, float u) {
  uint lo = 0, hi = uint(e.size()) - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (e[mid].cdf > u) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

// n equal emitters (as Sponza's 960 light triangles): cdf (k + 1) / n, so cdf steps fall exactly on
// the float starts of buckets, where one ulp decides the pick.
std::vector<Emitter> evenTable(uint n) {
  std::vector<Emitter> e(n);
  for (uint k = 0; k < n; ++k) e[k].cdf = float(double(k + 1) / double(n));
  fillEmitterGuide(e);
  return e;
}

// A cdf of n entries from random weights, some tiny (equal cdf floats in a row), the last 1.
std::vector<Emitter> randomTable(std::mt19937& rng, uint n) {
  std::uniform_real_distribution<double> w(0.0, 1.0);
  std::vector<double> weight(n);
  double total = 0.0;
  for (double& x : weight) {
    const double r = w(rng);
    x = r < 0.2 ? 1e-12 * r : (r < 0.3 ? 1e3 * r : r);
    total += x;
  }
  std::vector<Emitter> e(n);
  double running = 0.0;
  for (uint k = 0; k < n; ++k) {
    running += weight[k];
    e[k].cdf = float(running / total);
  }
  e.back().cdf = 1.0f;
  fillEmitterGuide(e);
  return e;
}

// The u worth checking: random ones, each cdf value and each bucket's start, one ulp either side.
std::vector<float> probes(std::mt19937& rng, const std::vector<Emitter>& e) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> u = {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, inf, -inf, std::nextafter(1.0f, 0.0f),
                          std::numeric_limits<float>::quiet_NaN()};
  std::uniform_real_distribution<float> r(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) u.push_back(r(rng));
  const uint n = uint(e.size());
  for (uint k = 0; k < n; ++k) {
    for (float x : {e[k].cdf, float(double(k) / n)}) {
      u.push_back(x);
      u.push_back(std::nextafter(x, -inf));
      u.push_back(std::nextafter(x, inf));
    }
  }
  return u;
}

}  // namespace

TEST_CASE("emitter guide: the guided pick equals a search of the whole table" * doctest::test_suite("cpu")) {
  std::mt19937 rng(7);
  int mismatches = 0, guided = 0;
  for (uint n : {1u, 2u, 3u, 15u, 16u, 17u, 31u, 49u, 64u, 100u, 255u, 960u, 1000u, 4097u, 6000u}) {
    for (int rep = 0; rep < 4; ++rep) {
      std::vector<Emitter> e = rep == 0 ? evenTable(n) : randomTable(rng, n);
      for (float u : probes(rng, e)) {
        const uint want = wholeSearch(e, u), got = pick_emitter(e.data(), n, u);
        if (got != want && mismatches++ < 5)
          MESSAGE("n " << n << " u " << u << ": guided " << got << ", whole table " << want);
        guided += n >= MCL_EMITTER_GUIDE_MIN;
      }
    }
  }
  CHECK(mismatches == 0);
  CHECK(guided > 10000);  // the guided branch ran
}

TEST_CASE("emitter guide: each bucket's range is narrow on an even table" * doctest::test_suite("cpu")) {
  // 960 equal emitters (Sponza's lights): a bucket's range spans at most three picks (the float
  // bucket starts and cdf steps straddle each other), so a pick takes at most two search steps.
  std::vector<Emitter> e = evenTable(960);
  uint widest = 0;
  for (uint b = 0; b + 1u < 960u; ++b) widest = std::max(widest, e[b + 1u].guide - e[b].guide);
  CHECK(widest <= 2u);
  CHECK(e[0].guide == 0u);
  CHECK(e[959].guide == 959u);
}

}  // namespace test_file_emitter_guide
