// test_estimator.cpp: the estimator knows its error. The standard error estimated from each
// render's own statistics matches the spread of the pixel means over independent seeds; adaptive
// sampling meets its target and saves samples; the accumulate stage keeps the variance of samples
// with a large mean (Welford).
#include <doctest/doctest.h>

#include <cmath>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "kernels/stages/stages.h"
#include "render/wavefront.h"
#include "stats.h"
#include "test_scenes.h"

using namespace montecl;
using namespace montecl_test;

namespace {

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
  const int seeds = 40;
  const std::size_t pixels = 64;
  std::vector<RunningStats> spread(pixels);
  std::vector<double> estimatedVar(pixels, 0.0);
  for (int seed = 0; seed < seeds; ++seed) {
    s.render.seed = std::uint32_t(seed);
    RenderStats stats;
    Film f = render(s, {}, stats);
    for (std::size_t p = 0; p < pixels; ++p) {
      double n = f.mean[p].w, m = f.mean[p].x;
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
  float mostSamples = 0;
  double worstConverged = 0;
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    double e = relativeStandardError(f, p, o.errorFloor);
    met += e <= o.targetError;
    if (e <= o.targetError) worstConverged = std::max(worstConverged, e);
    easy += f.mean[p].w == float(o.minSpp);
    mostSamples = std::max(mostSamples, f.mean[p].w);
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
  double total = 0;
  for (const auto& v : f.mean) total += v.w;
  CHECK(total == double(stats.samples));
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
  float4 mean(0.0f), m2(0.0f);
  RunningStats exact;
  const uint wave = 1000;
  std::vector<float4> radiance(wave), shadow(wave, float4(0.0f));
  for (uint start = 0; start < 100000; start += wave) {
    for (uint i = 0; i < wave; ++i) {
      float v = 1e4f + 0.1f * rng_uniform4(1u, 0u, start + i, 0u).x;
      radiance[i] = float4(v, v, v, 0.0f);
      exact.add(v);
    }
    accumulate_args args{};
    args.frame = &f;
    args.waveStart = start;
    args.waveCount = wave;
    args.active = active;
    args.radiance = radiance.data();
    args.shadowContrib = shadow.data();
    args.mean = &mean;
    args.m2 = &m2;
    stage_accumulate(&args, 0);
  }
  CHECK(mean.w == 100000.0f);
  CHECK(mean.x == doctest::Approx(exact.mean).epsilon(1e-6));
  double variance = m2.x / (mean.w - 1.0);
  INFO("variance " << variance << ", exact " << exact.variance());
  CHECK(variance == doctest::Approx(exact.variance()).epsilon(0.02));
}
