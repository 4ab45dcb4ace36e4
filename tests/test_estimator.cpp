// test_estimator.cpp: the estimator knows its error. The standard error estimated from each
// render's own sums matches the spread of the pixel means over independent seeds; adaptive
// sampling meets its target and saves samples; time limits and SIGINT stop a render and leave a
// valid image whose per-pixel sample counts are what was done.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "kernels/stages/stages.h"
#include "render/wavefront.h"
#include "stats.h"
#include "test_scenes.h"

extern char** environ;

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

TEST_CASE("the estimated standard error matches the spread over 40 seeds within 10%") {
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
      double n = f.sum[p].w, m = f.sum[p].x / n;
      double var = (f.sumSq[p].x / n - m * m) * n / (n - 1);
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

TEST_CASE("adaptive sampling meets its target on 99% of pixels with fewer samples than uniform") {
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
  for (std::size_t p = 0; p < f.sum.size(); ++p) {
    double e = relativeStandardError(f, p, o.errorFloor);
    met += e <= o.targetError;
    if (e <= o.targetError) worstConverged = std::max(worstConverged, e);
    easy += f.sum[p].w == float(o.minSpp);
    mostSamples = std::max(mostSamples, f.sum[p].w);
  }
  INFO("met " << met << " of " << f.sum.size() << ", easy " << easy << ", most samples " << mostSamples
              << ", total " << stats.samples << ", rounds " << stats.rounds);
  CHECK(met >= f.sum.size() * 99 / 100);
  CHECK(stats.converged == met);
  CHECK(easy > 0);
  CHECK(easy < f.sum.size());
  CHECK(worstConverged <= o.targetError);
  // Uniform sampling needs the hardest pixel's count everywhere for the same worst-pixel error.
  std::uint64_t uniformSamples = std::uint64_t(mostSamples) * f.sum.size();
  CHECK(stats.samples < uniformSamples);
  // The counts in the film are the samples done.
  double total = 0;
  for (const auto& v : f.sum) total += v.w;
  CHECK(total == double(stats.samples));
  MESSAGE("adaptive: " << stats.samples << " samples against " << uniformSamples << " uniform ("
                       << double(uniformSamples) / stats.samples << "x)");

  // Deterministic: the same again.
  RenderStats again;
  Film g = render(s, o, again);
  CHECK(g.sum == f.sum);
  CHECK(g.sumSq == f.sumSq);
}

TEST_CASE("--time stops after the wave that crosses the limit and writes the image so far") {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  CliResult r = runMontecl({"render", scene, "-o", dir.file("t.exr"), "--width", "64", "--height", "48", "--spp",
                            "1000000", "--time", "1", "--wave-size", "20000", "-q"});
  INFO(r.out << r.err);
  REQUIRE(r.exitCode == 0);
  LayeredImage img = readLayeredImage(dir.file("t.exr"));
  const std::vector<float>& n = *img.find("samples");
  float lo = *std::min_element(n.begin(), n.end()), hi = *std::max_element(n.begin(), n.end());
  CHECK(lo >= 1.0f);
  CHECK(hi - lo <= 1.0f);  // sample-major waves: counts differ by at most one
  CHECK(hi < 1000000.0f);
}

TEST_CASE("SIGINT finishes the wave, writes a valid image with its true sample counts, exits 130") {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  std::string out = dir.file("i.exr");
  std::vector<std::string> args = {MONTECL_EXE, "render", scene, "-o", out, "--width", "64", "--height", "48",
                                   "--spp", "1000000", "--wave-size", "20000", "-q"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, MONTECL_EXE, &actions, nullptr, argv.data(), environ) == 0);
  posix_spawn_file_actions_destroy(&actions);
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  kill(pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  LayeredImage img = readLayeredImage(out);
  CHECK(img.width == 64);
  const std::vector<float>& n = *img.find("samples");
  float lo = *std::min_element(n.begin(), n.end()), hi = *std::max_element(n.begin(), n.end());
  CHECK(hi - lo <= 1.0f);
  CHECK(hi < 1000000.0f);
  // The mean is finite everywhere a sample was taken.
  for (float v : *img.find("R")) REQUIRE(std::isfinite(v));
}

TEST_CASE("AOVs: first-hit albedo, facing normal and depth of a floor seen from above") {
  Scene s = floorScene({0, 0, 0}, 2.0f, 40.0f, 16, 4);
  s.materials[0].albedo = {0.25f, 0.5f, 0.75f};
  RenderOptions o;
  o.aovs = true;
  RenderStats stats;
  Film f = render(s, o, stats);
  REQUIRE(f.aovSum.size() == 2 * f.sum.size());
  const float maxDepth = 2.0f / std::cos(glm::radians(20.0f * std::sqrt(2.0f)));
  for (std::size_t p = 0; p < f.sum.size(); ++p) {
    const float n = f.sum[p].w;
    REQUIRE(f.aovSum[2 * p].x / n == 0.25f);
    REQUIRE(f.aovSum[2 * p].y / n == 0.5f);
    REQUIRE(f.aovSum[2 * p].z / n == 0.75f);
    REQUIRE(f.aovSum[2 * p + 1].y / n == 1.0f);  // the normal faces the camera above
    const float depth = f.aovSum[2 * p].w / n;
    REQUIRE(depth >= 2.0f * (1.0f - 1e-5f));
    REQUIRE(depth <= maxDepth);
  }
  // Without AOVs the film has none, and the radiance is the same.
  RenderStats plain;
  Film g = render(s, {}, plain);
  CHECK(g.aovSum.empty());
  CHECK(g.sum == f.sum);
}

TEST_CASE("--aov all writes named albedo, normal and depth channels; --aov with .png is bad input") {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  CliResult r = runMontecl({"render", scene, "-o", dir.file("a.exr"), "--width", "16", "--height", "12", "--spp",
                            "2", "--aov", "all", "-q"});
  REQUIRE(r.exitCode == 0);
  LayeredImage img = readLayeredImage(dir.file("a.exr"));
  for (const char* name : {"R", "G", "B", "samples", "var.R", "var.G", "var.B", "albedo.R", "albedo.G", "albedo.B",
                           "N.X", "N.Y", "N.Z", "Z"}) {
    CAPTURE(name);
    CHECK(img.find(name) != nullptr);
  }
  CliResult bad = runMontecl({"render", scene, "-o", dir.file("a.png"), "--aov", "albedo", "-q"});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("--aov") != std::string::npos);
}

TEST_CASE("accumulate keeps the variance of samples with a large mean (Welford, no cancellation)") {
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
