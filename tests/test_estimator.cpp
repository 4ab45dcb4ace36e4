// test_estimator.cpp: the estimator knows its error. The standard error estimated from each
// render's own statistics matches the spread of the pixel means over independent seeds; adaptive
// sampling meets its target and saves samples; the accumulate stage keeps the variance of samples
// with a large mean (Welford).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "kernels/stages/stages.h"
#include "render/sample_schedule.h"
#include "render/wavefront.h"
#include "film_stats.h"
#include "stats.h"
#include "test_scenes.h"

namespace test_file_estimator {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// One pixel's film state (kernels/stages/accumulate.h) driven through the accumulate stage on the host.
struct PixelState {
  float4 meanHi{0.0f}, meanLo{0.0f}, m2Hi{0.0f}, m2Lo{0.0f};
  void accumulate(const FrameParams& f, const uint* active, ulong start, uint wave, std::vector<float4>& radiance,
                  std::vector<float4>& shadow) {
    accumulate_args args{};
    args.frame = &f;
    args.waveStart = start;
    args.waveCount = wave;
    args.active = active;
    args.radiance = radiance.data();
    args.shadowContrib = shadow.data();
    args.mean = &meanHi;
    args.meanLo = &meanLo;
    args.m2 = &m2Hi;
    args.m2Lo = &m2Lo;
    stage_accumulate(&args, 0);
  }
  // n samples of value m (M2 = 0).
  void preset(std::uint64_t n, float m) {
    meanHi = float4(m, m, m, as_float(uint(n & 0xffffffffu)));
    meanLo = float4(0.0f, 0.0f, 0.0f, as_float(uint(n >> 32)));
    m2Hi = m2Lo = float4(0.0f);
  }
  std::uint64_t count() const { return std::uint64_t(as_uint(meanHi.w)) | (std::uint64_t(as_uint(meanLo.w)) << 32); }
  double mean(int c) const { return double(meanHi[c]) + double(meanLo[c]); }
  double m2(int c) const { return double(m2Hi[c]) + double(m2Lo[c]); }
};

Film render(const Scene& s, const RenderOptions& o, RenderStats& stats) {
  static const DeviceInfo device = selectDevice("");
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(device, o);
  return r.render(s, bvh, stats);
}

// Floor beside a wall, AO within distance 1: pixels farther than 1 from the wall are exactly 1
// (easy: zero variance), pixels near it vary (hard).
Scene easyAndHardScene(int size) {
  Scene s = wallScene(size, 1);
  s.camera.position = {-1.2f, 1.6f, 0.0f};
  s.camera.target = {-1.2f, 0.0f, 0.0f};
  s.camera.fovY = 60.0f;
  s.render.aoDistance = 1.0f;
  s.render.aoSampling = montecl::AoSampling::Cosine;
  return s;
}

}  // namespace

TEST_CASE("the estimated standard error matches the spread over 40 seeds within 10%" * doctest::test_suite("opencl slow")) {
  Scene s = wallScene(8, 16);
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.sampler = montecl::Sampler::Independent;  // var/n is the error of i.i.d. samples (sobol: the case below)
  const int seeds = 40;
  const std::size_t pixels = 64;
  std::vector<RunningStats> spread(pixels);
  std::vector<double> estimatedVar(pixels, 0.0);
  for (int seed = 0; seed < seeds; ++seed) {
    s.render.seed = std::uint32_t(seed);
    RenderStats stats;
    Film f = render(s, {}, stats);
    for (std::size_t p = 0; p < pixels; ++p) {
      double n = double(f.count[p]), m = f.mean[p].x;
      double var = f.variance(p, 0);
      spread[p].add(m);
      estimatedVar[p] += var / n / seeds;  // mean over seeds of the estimated variance of the mean
    }
  }
  double empirical = 0, estimated = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    empirical += spread[p].variance();
    estimated += estimatedVar[p];
  }
  double ratio = std::sqrt(empirical / estimated);
  INFO("empirical / estimated standard error = " << ratio);
  CHECK(ratio > 0.9);
  CHECK(ratio < 1.1);
}

TEST_CASE("adaptive sampling meets its target on 99% of pixels with fewer samples than uniform" * doctest::test_suite("opencl")) {
  Scene s = easyAndHardScene(24);
  RenderOptions o;
  o.targetError = 0.04;
  o.minSpp = 16;
  o.maxSpp = 2048;
  RenderStats stats;
  Film f = render(s, o, stats);
  std::size_t met = 0, easy = 0;
  std::uint64_t mostSamples = 0;
  double worstConverged = 0;
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    double e = relativeStandardError(f, p, o.errorFloor);
    met += e <= o.targetError;
    if (e <= o.targetError) worstConverged = std::max(worstConverged, e);
    easy += f.count[p] == std::uint64_t(o.minSpp);
    mostSamples = std::max(mostSamples, f.count[p]);
  }
  INFO("met " << met << " of " << f.mean.size() << ", easy " << easy << ", most samples " << mostSamples
              << ", total " << stats.samples << ", rounds " << stats.rounds);
  CHECK(met >= f.mean.size() * 99 / 100);
  CHECK(stats.converged == met);
  CHECK(easy > 0);
  CHECK(easy < f.mean.size());
  CHECK(worstConverged <= o.targetError);
  // Uniform sampling needs the hardest pixel's count everywhere for the same worst-pixel error.
  std::uint64_t uniformSamples = std::uint64_t(mostSamples) * f.mean.size();
  CHECK(stats.samples < uniformSamples);
  // The counts in the film are the samples done.
  std::uint64_t total = 0;
  for (std::uint64_t n : f.count) total += n;
  CHECK(total == stats.samples);
  MESSAGE("adaptive: " << stats.samples << " samples against " << uniformSamples << " uniform ("
                       << double(uniformSamples) / stats.samples << "x)");

  // Deterministic: the same again.
  RenderStats again;
  Film g = render(s, o, again);
  CHECK(g.mean == f.mean);
  CHECK(g.m2 == f.m2);
}

TEST_CASE("accumulate keeps the variance of samples with a large mean (Welford, no cancellation)" * doctest::test_suite("cpu")) {
  // 100k samples 1e4 + U(0, 0.1) through the accumulate stage in waves of 1000: the variance of
  // one sample must match the double-precision value (0.1^2 / 12) within 2%. With float sums of
  // x and x^2 it would be lost entirely (x^2 ~ 1e8, float spacing there ~ 8).
  FrameParams f{};
  f.width = f.height = 1;
  f.activeCount = 1;
  f.shadowSlots = 1;
  const uint active[1] = {0};
  PixelState px;
  RunningStats exact;
  const uint wave = 1000;
  std::vector<float4> radiance(wave), shadow(wave, float4(0.0f));
  for (uint start = 0; start < 100000; start += wave) {
    for (uint i = 0; i < wave; ++i) {
      float v = 1e4f + 0.1f * rng_uniform4(1u, 0u, start + i, 0u).x;
      radiance[i] = float4(v, v, v, 0.0f);
      exact.add(v);
    }
    px.accumulate(f, active, start, wave, radiance, shadow);
  }
  CHECK(px.count() == 100000u);
  CHECK(px.mean(0) == doctest::Approx(exact.mean).epsilon(1e-12));
  double variance = px.m2(0) / (double(px.count()) - 1.0);
  INFO("variance " << variance << ", exact " << exact.variance());
  CHECK(variance == doctest::Approx(exact.variance()).epsilon(1e-6));
}

TEST_CASE("accumulate: the mean does not drift past 2^24 samples, and the count is exact past 2^32" *
          doctest::test_suite("cpu")) {
  // A pixel that already holds n0 samples of mean m0 (the state after a long render of a small
  // light by BRDF sampling: mostly zeros, rarely a bright hit) takes 2^20 more such samples. A float
  // Welford mean loses delta / n to rounding near 2^24 samples (each zero lowers it by a whole ulp
  // instead of 0.73 of one): the result must match the exact combination, computed in double, to
  // 1e-9 relative, and the 64-bit count must be exact across 2^32.
  FrameParams f{};
  f.width = f.height = 1;
  f.activeCount = 1;
  f.shadowSlots = 1;
  const uint active[1] = {0};
  for (std::uint64_t n0 : {std::uint64_t(1) << 24, std::uint64_t(1) << 26, (std::uint64_t(1) << 32) - 1000}) {
    CAPTURE(n0);
    const double m0 = 0.0229;
    PixelState px;
    px.preset(n0, float(m0));
    double sum = double(float(m0)) * double(n0), added = 0.0;
    const uint wave = 4096, samples = 1u << 20;
    std::vector<float4> radiance(wave), shadow(wave, float4(0.0f));
    for (uint start = 0; start < samples; start += wave) {
      for (uint i = 0; i < wave; ++i) {
        float v = rng_uniform4(7u, 0u, start + i, 0u).x < 0.002f ? 11.45f : 0.0f;
        radiance[i] = float4(v, v, v, 0.0f);
        added += v;
      }
      px.accumulate(f, active, start, wave, radiance, shadow);
    }
    const std::uint64_t n = n0 + samples;
    CHECK(px.count() == n);
    const double exactMean = (sum + added) / double(n);
    CHECK(px.mean(0) == doctest::Approx(exactMean).epsilon(1e-9));
  }
}

// With the sobol sampler a pixel's samples are correlated: the error of the mean comes from the
// spread of the K independently scrambled sub-sequences' means (Film::meanVariance), and var / n
// overstates it. Measured against the spread of the pixel means over 40 seeds (independent
// scrambles): the squared errors agree within 20% (summed over the pixels), var / n is far off.
TEST_CASE("sobol: the sub-sequence error estimate matches the spread over 40 seeds within 20%; var/n does not" * doctest::test_suite("opencl slow")) {
  for (int spp : {16, 64}) {
    Scene s = wallScene(8, spp);
    s.render.aoSampling = montecl::AoSampling::Uniform;
    s.render.sampler = montecl::Sampler::Sobol;
    s.render.errorEstimate = true;  // the sub-sequences whose estimate is checked
    const int seeds = 40;
    const std::size_t pixels = 64;
    std::vector<RunningStats> spread(pixels);
    double estimated = 0.0, perSample = 0.0;
    for (int seed = 0; seed < seeds; ++seed) {
      s.render.seed = std::uint32_t(seed);
      RenderStats stats;
      Film f = render(s, {}, stats);
      REQUIRE(f.splits() == 4u);
      for (std::size_t p = 0; p < pixels; ++p) {
        spread[p].add(f.meanOf(p, 0));
        estimated += f.meanVariance(p, 0) / seeds;
        perSample += f.variance(p, 0) / double(f.count[p]) / seeds;
      }
    }
    double empirical = 0.0;
    for (std::size_t p = 0; p < pixels; ++p) empirical += spread[p].variance();
    INFO(spp << " spp: empirical / estimated squared error = " << empirical / estimated
              << ", empirical / (var / n) = " << empirical / perSample);
    CHECK(empirical > 0.0);
    CHECK(empirical / estimated > 0.8);
    CHECK(empirical / estimated < 1.2);
    CHECK(empirical / perSample < 0.5);  // the i.i.d. estimate, not valid here
  }
}

// The default render (no error estimate asked for) is one Owen-scrambled sequence per pixel, the
// lowest error: its MSE at equal spp, measured as the spread of the pixel means over 24 seeds, is
// within 10% of one sequence's (sobol_splits 1), while the 4 sub-sequences of the estimate cost
// about 3x (measured here: checked > 1.5x, so the comparison can tell them apart).
TEST_CASE("sobol: the default image's MSE at equal spp is within 10% of one sequence's" * doctest::test_suite("opencl slow")) {
  const int seeds = 24;
  const std::size_t pixels = 64;
  auto mse = [&](bool estimate, int splits) {
    Scene s = wallScene(8, 64);
    s.render.aoSampling = montecl::AoSampling::Uniform;
    if (estimate) {
      s.render.errorEstimate = true;
      s.render.sobolSplits = splits;
    }
    std::vector<RunningStats> spread(pixels);
    for (int seed = 0; seed < seeds; ++seed) {
      s.render.seed = std::uint32_t(seed);
      RenderStats stats;
      Film f = render(s, {}, stats);
      for (std::size_t p = 0; p < pixels; ++p) spread[p].add(f.meanOf(p, 0));
    }
    double sum = 0.0;
    for (std::size_t p = 0; p < pixels; ++p) sum += spread[p].variance();
    return sum / double(pixels);
  };
  const double defaultMse = mse(false, 0), oneSequence = mse(true, 1), fourSplits = mse(true, 4);
  INFO("MSE: default " << defaultMse << ", one sequence " << oneSequence << ", 4 sub-sequences " << fourSplits);
  CHECK(RenderSettings().sampler == montecl::Sampler::Sobol);
  CHECK(oneSequence > 0.0);
  CHECK(defaultMse / oneSequence > 0.9);
  CHECK(defaultMse / oneSequence < 1.1);
  CHECK(fourSplits / oneSequence > 1.5);
  // Without sub-sequences the default film still says its samples are correlated, so the test
  // fixtures refuse var/n on it as they do on a film with them.
  RenderStats stats;
  const Film f = render(wallScene(8, 4), {}, stats);
  CHECK(f.splits() == 0u);
  CHECK(f.correlated);
  CHECK_THROWS_AS(requireIndependentSamples(f), std::logic_error);
}

// Adaptive sampling with sobol stops each pixel on the sub-sequence estimate: 99% of the pixels
// meet the target by it, and the error they really have (against the mean of 8 renders with other
// seeds at the maximum count) is within the target over the pixels that are not exact with K = 8
// sub-sequences; with the default K = 4 the estimate has 3 degrees of freedom per pixel, pixels
// that underestimate stop early, and the real RMS error is up to 1.3 times the target (measured 1.21).
TEST_CASE("adaptive sampling with sobol meets its target on 99% of pixels, and the real error too" * doctest::test_suite("opencl slow uninstrumented")) {
  for (const auto& row : {std::pair<int, double>{4, 1.3}, std::pair<int, double>{8, 1.0}}) {
    const int splits = row.first;
    const double allowed = row.second;
    Scene s = easyAndHardScene(24);
    s.render.sampler = montecl::Sampler::Sobol;
    s.render.sobolSplits = splits;
    s.render.errorEstimate = true;  // as the CLI's --target-error asks
    RenderOptions o;
    o.targetError = 0.02;
    o.minSpp = 16;
    o.maxSpp = 2048;
    RenderStats stats;
    Film f = render(s, o, stats);
    const std::size_t pixels = f.mean.size();
    std::size_t met = 0, easy = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
      met += relativeStandardError(f, p, o.errorFloor) <= o.targetError;
      easy += f.count[p] == std::uint64_t(o.minSpp);
    }
    CHECK(met >= pixels * 99 / 100);
    CHECK(stats.converged == met);
    CHECK(easy > 0);
    CHECK(easy < pixels);
    Scene r = s;
    r.render.spp = 2048;
    std::vector<double> reference(pixels, 0.0);
    for (std::uint32_t seed = 100; seed < 108; ++seed) {
      r.render.seed = seed;
      RenderStats rs;
      Film g = render(r, {}, rs);
      for (std::size_t p = 0; p < pixels; ++p) reference[p] += g.meanOf(p, 0) / 8.0;
    }
    double squared = 0.0;
    std::size_t counted = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
      if (f.count[p] == std::uint64_t(o.minSpp) && f.meanVariance(p, 0) == 0.0) continue;  // exact pixels
      const double e = (f.meanOf(p, 0) - reference[p]) / std::max(reference[p], o.errorFloor);
      squared += e * e, ++counted;
    }
    const double rms = std::sqrt(squared / double(std::max<std::size_t>(counted, 1)));
    INFO("K " << splits << ": met " << met << " of " << pixels << ", easy " << easy << ", samples " << stats.samples
              << ", real relative RMS error " << rms << " over " << counted << " pixels, target " << o.targetError);
    CHECK(counted > 0);
    CHECK(rms <= allowed * o.targetError);
  }
}

}  // namespace test_file_estimator
