// test_sobol.cpp: the Owen-scrambled Sobol sampler of kernels/shared/sobol.h and sampler.h on the
// CPU: stratification of one pixel's first 2^m points (elementary intervals), equality with a
// reference written here independently (Sobol from explicit direction numbers, a bit-by-bit
// reversal and scramble), scrambles that differ per pixel, seed and set, the sampler switch.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <vector>

#include "kernels/shared/sampler.h"

namespace test_file_sobol {  // keeps this file's helpers apart in a unity batch

namespace {

// Joe-Kuo new-joe-kuo-6.21201, dimensions 2..4 (1-based): degree s, coefficients a, initial m.
struct JoeKuo {
  int s;
  unsigned a;
  std::vector<uint> m;
};
const JoeKuo kJoeKuo[3] = {{1, 0, {1}}, {2, 1, {1, 3}}, {3, 1, {1, 3, 1}}};

// The 32 direction numbers (left-aligned) of Sobol dimension d (0: van der Corput), by Bratley and
// Fox's recurrence on the integers m_k.
std::vector<uint> directions(int d) {
  std::vector<uint> v(32);
  if (d == 0) {
    for (int k = 0; k < 32; ++k) v[size_t(k)] = 1u << (31 - k);
    return v;
  }
  const JoeKuo& jk = kJoeKuo[d - 1];
  std::vector<unsigned long long> m(jk.m.begin(), jk.m.end());
  for (int k = jk.s; k < 32; ++k) {
    unsigned long long x = m[size_t(k - jk.s)] ^ (m[size_t(k - jk.s)] << jk.s);
    for (int i = 1; i < jk.s; ++i)
      if ((jk.a >> (jk.s - 1 - i)) & 1u) x ^= m[size_t(k - i)] << i;
    m.push_back(x);
  }
  for (int k = 0; k < 32; ++k) v[size_t(k)] = uint(m[size_t(k)] << (31 - k));
  return v;
}

uint plainSobol(uint i, int d) {
  static const std::vector<uint> dirs[4] = {directions(0), directions(1), directions(2), directions(3)};
  uint x = 0;
  for (int k = 0; k < 32; ++k)
    if ((i >> k) & 1u) x ^= dirs[d][size_t(k)];
  return x;
}

uint reverseByLoop(uint x) {
  uint r = 0;
  for (int k = 0; k < 32; ++k) r |= ((x >> k) & 1u) << (31 - k);
  return r;
}

// Burley's hash-based nested uniform scramble, written out: on the reversed bits, add the seed,
// then four rounds of x ^= x * c (constants from the paper), reverse back.
uint referenceOwen(uint x, uint seed) {
  const uint c[4] = {0x6c50b47cu, 0xb82f1e52u, 0xc7afe638u, 0x8d22f6e6u};
  uint y = reverseByLoop(x) + seed;
  for (uint k : c) y ^= y * k;
  return reverseByLoop(y);
}

// The five scramble seeds hashed from (seed, pixel, set) as sobol.h states them: pcg4d's four
// outputs (the index's seed, then dimensions 0..2) and a mix of the first for dimension 3.
RngOut referencePoint(uint seed, uint pixel, uint sample, uint set) {
  RngOut h = pcg4d(pixel, mcl_mix32(set), seed, 0x50b01u);
  uint index = referenceOwen(sample, h.x);
  RngOut r;
  r.x = referenceOwen(plainSobol(index, 0), h.y);
  r.y = referenceOwen(plainSobol(index, 1), h.z);
  r.z = referenceOwen(plainSobol(index, 2), h.w);
  r.w = referenceOwen(plainSobol(index, 3), mcl_mix32(h.x ^ 0x9e3779b9u));
  return r;
}

uint component(const RngOut& r, int d) { return d == 0 ? r.x : d == 1 ? r.y : d == 2 ? r.z : r.w; }

// Whether every elementary interval [i 2^-a, (i+1) 2^-a) x [j 2^-b, (j+1) 2^-b) with a + b = m - t
// holds exactly 2^t of the first 2^m points of (pixel, set) in dimensions (d0, d1).
bool stratified(uint seed, uint pixel, uint set, int d0, int d1, int m, int t) {
  std::vector<RngOut> pts;
  for (uint i = 0; i < (1u << m); ++i) pts.push_back(sobol_owen4_bits(seed, pixel, i, set));
  for (int a = 0; a <= m - t; ++a) {
    const int b = m - t - a;
    std::map<std::pair<uint, uint>, int> cells;
    for (const RngOut& p : pts) {
      uint x = component(p, d0), y = component(p, d1);
      cells[{a ? x >> (32 - a) : 0u, b ? y >> (32 - b) : 0u}]++;
    }
    if (cells.size() != (1u << (m - t))) return false;
    for (const auto& cell : cells)
      if (cell.second != (1 << t)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("sobol: the recurrence's direction numbers and the reversal are the Joe-Kuo table's" * doctest::test_suite("cpu")) {
  for (uint i = 0; i < 4096; ++i) {
    RngOut p = mcl_sobol4(i);
    REQUIRE(p.x == plainSobol(i, 0));
    REQUIRE(p.y == plainSobol(i, 1));
    REQUIRE(p.z == plainSobol(i, 2));
    REQUIRE(p.w == plainSobol(i, 3));
    REQUIRE(mcl_reverse_bits(i * 2654435761u) == reverseByLoop(i * 2654435761u));
  }
  for (uint i : {0xffffffffu, 0x80000001u, 0xdeadbeefu}) {
    RngOut p = mcl_sobol4(i);  // the high index bits count too (a scrambled index is anywhere)
    CHECK(p.w == plainSobol(i, 3));
  }
}

TEST_CASE("sobol: scrambled points equal the reference written here, and are not the plain Sobol points" * doctest::test_suite("cpu")) {
  int same = 0;
  for (uint pixel : {0u, 1u, 77u, 4095u})
    for (uint set : {MCL_DIM_CAMERA, MCL_DIM_LIGHT, MCL_DIM_PATH + 3u})
      for (uint i = 0; i < 512; ++i) {
        RngOut a = sobol_owen4_bits(9u, pixel, i, set), b = referencePoint(9u, pixel, i, set);
        REQUIRE(a.x == b.x);
        REQUIRE(a.y == b.y);
        REQUIRE(a.z == b.z);
        REQUIRE(a.w == b.w);
        RngOut plain = mcl_sobol4(i);
        same += (a.x >> 8) == (plain.x >> 8);
      }
  CHECK(same < 4);  // unscrambled points would match every time
}

TEST_CASE("sobol: the scramble is nested uniform: a shared prefix stays shared, the next bit flips for half the seeds" * doctest::test_suite("cpu")) {
  for (int j = 0; j < 31; ++j) {
    int flips = 0;
    const int seeds = 4000;
    for (int s = 0; s < seeds; ++s) {
      uint seed = pcg4d(uint(s), uint(j), 1u, 2u).x;
      uint x = pcg4d(uint(s), 7u, uint(j), 3u).x, y = x ^ (1u << (31 - j));  // differ first at bit j
      uint sx = mcl_owen_scramble(x, seed), sy = mcl_owen_scramble(y, seed);
      uint prefix = j ? ~0u << (32 - j) : 0u;
      REQUIRE((sx & prefix) == (sy & prefix));
      REQUIRE((((sx ^ sy) >> (31 - j)) & 1u) == 1u);  // a bijection on each prefix's subtree
      flips += ((sx ^ x) >> (31 - j)) & 1u;
    }
    INFO("bit " << j << " flipped for " << flips << " of " << seeds << " seeds");
    CHECK(std::fabs(flips - seeds / 2.0) < 4.0 * std::sqrt(seeds / 4.0));
  }
}

TEST_CASE("sobol: one pixel's first 2^m points fill every elementary interval exactly, dims (0,1) and (2,3)" * doctest::test_suite("cpu")) {
  for (uint pixel : {0u, 5u, 1234u})
    for (uint set : {MCL_DIM_CAMERA, MCL_DIM_AO, MCL_DIM_PATH + MCL_DIM_PATH_STRIDE})
      for (int m = 1; m <= 12; ++m) {
        CAPTURE(pixel);
        CAPTURE(set);
        CAPTURE(m);
        CHECK(stratified(3u, pixel, set, 0, 1, m, 0));  // (0, 1) is a (0, 2)-sequence
        // Sobol dimensions 2 and 3 have t = 2 for m <= 12 (t computed from the direction numbers):
        // every interval of area 2^(2 - m) holds exactly 4 points.
        if (m >= 2) CHECK(stratified(3u, pixel, set, 2, 3, m, 2));
      }
  // 1D: every dimension alone is a (0, 1)-sequence.
  for (int d = 0; d < 4; ++d)
    for (int m = 1; m <= 12; ++m) {
      std::vector<int> cells(1u << m, 0);
      for (uint i = 0; i < (1u << m); ++i) cells[component(sobol_owen4_bits(3u, 42u, i, MCL_DIM_LIGHT), d) >> (32 - m)]++;
      bool ok = true;
      for (int c : cells) ok = ok && c == 1;
      CAPTURE(d);
      CAPTURE(m);
      CHECK(ok);
    }
}

TEST_CASE("sobol: pixels, seeds and sets get different scrambles; sets are uncorrelated within a pixel" * doctest::test_suite("cpu")) {
  auto sequence = [](uint seed, uint pixel, uint set) {
    std::vector<uint> v;
    for (uint i = 0; i < 64; ++i) v.push_back(sobol_owen4_bits(seed, pixel, i, set).x);
    return v;
  };
  CHECK(sequence(1u, 10u, MCL_DIM_CAMERA) != sequence(1u, 11u, MCL_DIM_CAMERA));
  CHECK(sequence(1u, 10u, MCL_DIM_CAMERA) != sequence(2u, 10u, MCL_DIM_CAMERA));
  CHECK(sequence(1u, 10u, MCL_DIM_CAMERA) != sequence(1u, 10u, MCL_DIM_BRDF));
  // Pearson r between the same dimension of two sets over many pixels' first 16 samples: the sets
  // are decorrelated by their seeds (a shared seed would give r = 1).
  const uint sets[] = {MCL_DIM_CAMERA, MCL_DIM_AO, MCL_DIM_LIGHT, MCL_DIM_LENS, MCL_DIM_PATH, MCL_DIM_PATH + 1u,
                       MCL_DIM_PATH + MCL_DIM_PATH_STRIDE, MCL_DIM_MIX, MCL_DIM_MIX + 1u};
  const int n = 2048 * 16;
  for (uint a : sets)
    for (uint b : sets) {
      if (a >= b) continue;
      for (int d = 0; d < 4; ++d) {
        double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
        for (int i = 0; i < n; ++i) {
          double x = u32_to_unit(component(sobol_owen4_bits(0u, uint(i / 16), uint(i % 16), a), d));
          double y = u32_to_unit(component(sobol_owen4_bits(0u, uint(i / 16), uint(i % 16), b), d));
          sx += x; sy += y; sxx += x * x; syy += y * y; sxy += x * y;
        }
        double cov = sxy / n - sx / n * sy / n;
        double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
        INFO("sets " << a << " and " << b << ", dimension " << d << ": r = " << r);
        CHECK(std::fabs(r) < 5.0 / std::sqrt(double(n)));
      }
    }
}

TEST_CASE("sampler: independent is rng_uniform4 bit for bit; sobol couples the first light sample to the camera set" * doctest::test_suite("cpu")) {
  FrameParams f{};
  f.seed = 11u;
  f.sobolSplits = 1u;  // one sequence per pixel: the points are sobol_owen4_bits' own
  for (uint group : {MCL_DIM_CAMERA, MCL_DIM_LIGHT, MCL_DIM_LIGHT + 1u, MCL_DIM_PATH + 1u, MCL_DIM_LENS})
    for (uint i = 0; i < 256; ++i) {
      f.sampler = MCL_SAMPLER_INDEPENDENT;
      float4 a = sample_uniform4(&f, 3u * i, i, group), b = rng_uniform4(11u, 3u * i, i, group);
      REQUIRE(a == b);
      f.sampler = MCL_SAMPLER_SOBOL;
      float4 s = sample_uniform4(&f, 3u * i, i, group);
      RngOut own = sobol_owen4_bits(11u, 3u * i, i, group), cam = sobol_owen4_bits(11u, 3u * i, i, MCL_DIM_CAMERA);
      const bool coupled = group == MCL_DIM_LIGHT || group == MCL_DIM_PATH + 1u;
      REQUIRE(s.x == u32_to_unit(own.x));
      REQUIRE(s.y == u32_to_unit(coupled ? cam.z : own.y));
      REQUIRE(s.z == u32_to_unit(coupled ? cam.w : own.z));
      REQUIRE(s.w == u32_to_unit(coupled ? own.y : own.w));
    }
}

}  // namespace test_file_sobol
