// test_adaptive_budget.cpp: adaptive sampling under a budget (render.adaptive, --adaptive): at the
// same total samples its relMSE over 16 seeds is below a uniform render's on a scene with an exact
// (bright, unoccluded) half and a noisy (dark, occluded) half; the image is bit-identical across
// devices and wave sizes; a render stopped after a wave and resumed from that wave's film (what a
// checkpoint holds, round targets included) equals an uninterrupted one; the error estimate it
// writes stays calibrated; two adaptive renders merge by their counts; bad combinations are one
// line and exit 2.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "render/checkpoint.h"
#include "render/wavefront.h"
#include "stats.h"
#include "test_scenes.h"

namespace test_file_adaptive_budget {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

Film render(const DeviceInfo& device, const Scene& s, const RenderOptions& o = {}, RenderStats* statsOut = nullptr,
            const RenderPart& part = {}) {
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(device, o);
  RenderStats stats;
  Film f = r.render(s, bvh, stats, {}, part);
  if (statsOut) *statsOut = stats;
  return f;
}

const DeviceInfo& openclDevice() {
  static const DeviceInfo device = selectDevice("");
  return device;
}

// Floor beside a wall, AO within distance 1, seen from above: the half of the image farther than
// 1 from the wall is exactly 1 (bright, no variance), the half near it is darker and noisy.
Scene halvesScene(int size, int spp) {
  Scene s = wallScene(size, spp);
  s.camera.position = {-1.4f, 1.6f, 0.0f};  // x from about -2.3 to -0.5: a quarter within 1 of the wall
  s.camera.target = {-1.4f, 0.0f, 0.0f};
  s.camera.fovY = 60.0f;
  s.render.aoDistance = 1.0f;
  s.render.aoSampling = AoSampling::Cosine;  // each sample is V: exactly 1 where nothing is within 1
  return s;
}

// relMSE of a film against a reference (per pixel and channel: (x - r)^2 / (r^2 + 0.01)).
double relMse(const Film& f, const std::vector<double>& reference) {
  double sum = 0.0;
  for (std::size_t p = 0; p < f.pixelCount(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double r = reference[3 * p + std::size_t(c)], d = f.meanOf(p, c) - r;
      sum += d * d / (r * r + 0.01);
    }
  return sum / double(3 * f.pixelCount());
}

bool sameBits(const Film& a, const Film& b) {
  return a.count == b.count && a.mean == b.mean && a.meanLo == b.meanLo && a.m2 == b.m2 && a.m2Lo == b.m2Lo &&
         a.split == b.split;
}

}  // namespace

TEST_CASE("adaptive budget: every pixel gets the first pass, the total is the budget, the dark half gets more" * doctest::test_suite("opencl")) {
  Scene s = halvesScene(16, 32);
  s.render.errorEstimate = true;  // as --adaptive asks
  s.render.adaptive = true;
  RenderStats stats;
  Film f = render(openclDevice(), s, {}, &stats);
  std::uint64_t total = 0, exactSamples = 0, noisySamples = 0, exactPixels = 0;
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    CHECK(f.count[p] >= 16);
    CHECK(f.count[p] % 4 == 0);  // whole rounds of the 4 sub-sequences
    total += f.count[p];
    const bool exact = f.meanVariance(p, 0) == 0.0 && f.meanOf(p, 0) == 1.0;
    (exact ? exactSamples : noisySamples) += f.count[p];
    exactPixels += exact;
  }
  CHECK(total == stats.samples);
  CHECK(total == std::uint64_t(32) * f.pixelCount());
  REQUIRE(exactPixels > 0);
  REQUIRE(exactPixels < f.pixelCount());
  const double exactSpp = double(exactSamples) / double(exactPixels),
               noisySpp = double(noisySamples) / double(f.pixelCount() - exactPixels);
  MESSAGE("exact pixels " << exactPixels << " at " << exactSpp << " spp, the others at " << noisySpp << " spp");
  CHECK(noisySpp > 2.0 * exactSpp);
}

TEST_CASE("adaptive budget: over 16 seeds its relMSE is below the uniform render's at the same total samples" * doctest::test_suite("opencl slow")) {
  for (Sampler sampler : {Sampler::Independent, Sampler::Sobol}) {
    Scene s = halvesScene(16, 32);
    s.render.sampler = sampler;
    s.render.errorEstimate = true;  // the adaptive render's, and the uniform one's alike (the same sub-sequences)
    std::vector<double> reference(3 * 256, 0.0);
    Scene ref = s;
    ref.render.spp = 4096;
    ref.render.errorEstimate = false;
    ref.render.seed = 1000;
    const Film r = render(openclDevice(), ref);
    for (std::size_t p = 0; p < r.pixelCount(); ++p)
      for (int c = 0; c < 3; ++c) reference[3 * p + std::size_t(c)] = r.meanOf(p, c);
    double adaptive = 0.0, uniform = 0.0, defaultUniform = 0.0;
    for (std::uint32_t seed = 0; seed < 16; ++seed) {
      s.render.seed = seed;
      s.render.adaptive = false;
      uniform += relMse(render(openclDevice(), s), reference) / 16.0;
      Scene plain = s;
      plain.render.errorEstimate = false;  // the default render: one sequence per pixel under sobol
      defaultUniform += relMse(render(openclDevice(), plain), reference) / 16.0;
      s.render.adaptive = true;
      RenderStats stats;
      adaptive += relMse(render(openclDevice(), s, {}, &stats), reference) / 16.0;
      CHECK(stats.samples == std::uint64_t(32) * 256);
    }
    MESSAGE(std::string(sampler == Sampler::Sobol ? "sobol" : "independent") << ": relMSE adaptive " << adaptive << ", uniform "
                                                                  << uniform << " (" << uniform / adaptive
                                                                  << "x), default uniform " << defaultUniform);
    CHECK(adaptive < 0.8 * uniform);
  }
}

// Under --time a render stops after the wave that crosses the limit, part-way through a round;
// the same stop rule on a sample count (through the interrupt flag the time limit shares) makes it
// repeatable: stopped at 48 spp on average, part-way through its third round, against a uniform
// 48-spp render (normalised by the samples each took: the adaptive one overshoots by under a wave).
TEST_CASE("adaptive budget: stopped part-way like --time, its relMSE over 16 seeds is below the uniform render's" * doctest::test_suite("opencl slow")) {
  Scene s = halvesScene(16, 48);
  s.render.errorEstimate = true;
  std::vector<double> reference(3 * 256, 0.0);
  Scene ref = s;
  ref.render.spp = 4096;
  ref.render.seed = 1000;
  const Film r = render(openclDevice(), ref);
  for (std::size_t p = 0; p < r.pixelCount(); ++p)
    for (int c = 0; c < 3; ++c) reference[3 * p + std::size_t(c)] = r.meanOf(p, c);
  const std::uint64_t stopAt = 48 * 256;
  double adaptive = 0.0, uniform = 0.0;
  for (std::uint32_t seed = 0; seed < 16; ++seed) {
    s.render.seed = seed;
    s.render.adaptive = false;
    s.render.spp = 48;
    uniform += relMse(render(openclDevice(), s), reference) / 16.0;
    s.render.adaptive = true;
    s.render.spp = 1024;  // a budget it will not reach
    volatile int stop = 0;
    RenderOptions o;
    o.waveSize = 64;
    o.interrupt = &stop;
    Bvh bvh = buildBvh(s.triangles);
    WavefrontRenderer renderer(openclDevice(), o);
    RenderStats stats;
    RenderPart part;
    part.afterWave = [](const std::function<Film()>&) {};  // as under --time: no wave queued ahead
    const Film f = renderer.render(s, bvh, stats, [&](std::uint64_t done, std::uint64_t, const RenderStats&) {
      if (done >= stopAt) stop = 1;
    }, part);
    REQUIRE(stats.stoppedEarly);
    REQUIRE(stats.samples >= stopAt);
    REQUIRE(stats.samples < stopAt + 64);
    adaptive += relMse(f, reference) * double(stats.samples) / double(stopAt) / 16.0;
  }
  MESSAGE("stopped at 48 spp: relMSE adaptive " << adaptive << ", uniform " << uniform << " (" << uniform / adaptive << "x)");
  CHECK(adaptive < 0.8 * uniform);
}

TEST_CASE("adaptive budget: bit-identical on the host backend and OpenCL, for any wave size and lane width" * doctest::test_suite("opencl")) {
  Scene s = halvesScene(12, 24);
  s.render.errorEstimate = true;
  s.render.adaptive = true;
  s.render.seed = 5;
  const Film reference = render(openclDevice(), s);
  const DeviceInfo host = selectDevice("host");
  for (std::uint64_t wave : {0ull, 37ull, 1000ull}) {
    RenderOptions o;
    o.waveSize = wave;
    CHECK_MESSAGE(sameBits(render(openclDevice(), s, o), reference), "OpenCL, wave size " << wave);
    CHECK_MESSAGE(sameBits(render(host, s, o), reference), "host, wave size " << wave);
  }
  for (unsigned lanes : {1u, 4u, 8u}) {
    RenderOptions o;
    o.lanes = lanes;
    CHECK_MESSAGE(sameBits(render(openclDevice(), s, o), reference), "OpenCL, " << lanes << " lanes");
  }
}

TEST_CASE("adaptive budget: a render stopped after a wave resumes from that wave's film (a checkpoint) bit-identically" * doctest::test_suite("opencl")) {
  Scene s = halvesScene(12, 64);
  s.render.errorEstimate = true;
  s.render.adaptive = true;
  RenderOptions o;
  // Waves of 50: the first pass (144 x 16 samples) ends in wave 47, the round to 32 spp in wave 93,
  // the one to 64 spp in wave 185; the stops fall in each.
  o.waveSize = 50;
  const Film whole = render(openclDevice(), s, o);
  TempDir dir;
  for (int stopAfter : {3, 60, 120}) {
    volatile int stop = 0;
    int waves = 0;
    Film saved;
    RenderPart part;
    part.afterWave = [&](const std::function<Film()>& readFilm) {
      if (++waves == stopAfter) saved = readFilm(), stop = 1;
    };
    RenderOptions stopping = o;
    stopping.interrupt = &stop;
    RenderStats stats;
    render(openclDevice(), s, stopping, &stats, part);
    REQUIRE(stop == 1);
    CHECK(stats.stoppedEarly);
    REQUIRE(saved.roundTarget.size() == saved.pixelCount());
    // Through the checkpoint file, as --checkpoint / --resume do.
    CheckpointInfo info = checkpointInfo(s, o);
    CHECK(info.adaptive);
    const std::string path = dir.file("run.ckpt");
    writeCheckpoint(path, info, saved);
    const Film loaded = readCheckpoint(path, info, saved.width, saved.height);
    CHECK(loaded.roundTarget == saved.roundTarget);
    RenderPart resume;
    resume.initialFilm = &loaded;
    RenderOptions other = o;
    other.waveSize = 0;  // another wave size after the resume
    CHECK_MESSAGE(sameBits(render(openclDevice(), s, other, nullptr, resume), whole), "stopped after wave " << stopAfter);
    // The targets are what makes it exact: past the first pass, a film without them starts a new
    // round from a mid-round film, and the image differs (a control that the check can fail).
    if (stopAfter > 3) {
      Film bare = loaded;
      bare.roundTarget.clear();
      resume.initialFilm = &bare;
      CHECK_MESSAGE(!sameBits(render(openclDevice(), s, other, nullptr, resume), whole), "no targets, wave " << stopAfter);
    }
  }
}

// The error estimate it writes (err.*: the sub-sequences' spread) against the spread of the pixel
// means over 40 seeds: the allocation reads the estimate, so a pixel whose estimate came out low
// gets fewer samples; the 3x3 averaging of the weights keeps that from skewing the calibration.
TEST_CASE("adaptive budget: the estimated error matches the spread over 40 seeds within 20%" * doctest::test_suite("opencl slow")) {
  Scene s = halvesScene(8, 32);
  s.render.sampler = Sampler::Sobol;
  s.render.errorEstimate = true;
  s.render.adaptive = true;
  const int seeds = 40;
  std::vector<RunningStats> spread(64);
  double estimated = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    s.render.seed = std::uint32_t(seed);
    const Film f = render(openclDevice(), s);
    REQUIRE(f.splits() == 4u);
    for (std::size_t p = 0; p < 64; ++p) {
      spread[p].add(f.meanOf(p, 0));
      estimated += f.meanVariance(p, 0) / seeds;
    }
  }
  double empirical = 0.0;
  for (const RunningStats& r : spread) empirical += r.variance();
  MESSAGE("empirical / estimated squared error = " << empirical / estimated);
  CHECK(empirical > 0.0);
  CHECK(empirical / estimated > 0.8);
  CHECK(empirical / estimated < 1.2);
}

TEST_CASE("adaptive budget: --adaptive with --target-error, or a budget above --max-spp, is one line, exit 2" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string out = dir.file("out.exr");
  struct Case {
    std::vector<std::string> extra;
    const char* named;
  };
  for (const Case& c : {Case{{"--adaptive", "--target-error", "0.05"}, "--adaptive"},
                        Case{{"--adaptive", "--spp", "64", "--max-spp", "32"}, "--max-spp"}}) {
    CliResult r = renderOnHost(demoScene(), out, c.extra);
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(c.named) != std::string::npos);
    CHECK(!std::filesystem::exists(out));
  }
}

TEST_CASE("adaptive budget: --adaptive writes the per-pixel counts and a resumed --time render equals the whole one" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  // Path traced, so that the time-limited run (a checkpoint written after every small wave) stops
  // part-way through a round on this machine; where it finishes the comparison still holds.
  const std::vector<std::string> common{"--adaptive", "--spp", "64", "--min-spp", "8", "--integrator", "path"};
  std::vector<std::string> whole = common;
  CliResult a = renderOnHost(demoScene(), dir.file("whole.exr"), whole, {}, 24, 24);
  REQUIRE_MESSAGE(a.exitCode == 0, a.err);
  CHECK(a.out.find("adaptive: ") != std::string::npos);
  // A short time limit that checkpoints after every wave, then the rest from the checkpoint.
  std::vector<std::string> first = common;
  for (const char* x : {"--time", "0.1", "--wave-size", "64", "--checkpoint", "", "--checkpoint-every", "1e-9"})
    first.push_back(x);
  first[first.size() - 3] = dir.file("run.ckpt");
  CliResult b = renderOnHost(demoScene(), dir.file("part.exr"), first, {}, 24, 24);
  REQUIRE_MESSAGE(b.exitCode == 0, b.err);
  MESSAGE("the time-limited run " << std::string(b.out.find("time limit reached") != std::string::npos ? "stopped part-way" : "finished"));
  std::vector<std::string> rest = common;
  rest.push_back("--resume");
  rest.push_back(dir.file("run.ckpt"));
  CliResult c = renderOnHost(demoScene(), dir.file("resumed.exr"), rest, {}, 24, 24);
  REQUIRE_MESSAGE(c.exitCode == 0, c.err);
  const LayeredImage w = readLayeredImage(dir.file("whole.exr")), r = readLayeredImage(dir.file("resumed.exr"));
  REQUIRE(w.channels == r.channels);
  const std::vector<float>* samples = w.find("samples");
  REQUIRE(samples);
  CHECK(*std::min_element(samples->begin(), samples->end()) < *std::max_element(samples->begin(), samples->end()));
  for (std::size_t k = 0; k < w.channels.size(); ++k) CHECK_MESSAGE(w.planes[k] == r.planes[k], w.channels[k]);
}

// Without --spp on the command line, --time is the budget: the scene file's spp (the demo's 64)
// does not stop it; every pixel may go up to --max-spp.
TEST_CASE("adaptive budget: --adaptive --time without --spp spends the time, not the scene's spp" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  CliResult r = runMontecl({"render", demoScene(), "-o", dir.file("t.exr"), "--width", "8", "--height", "8", "-q",
                            "--device", "host", "--adaptive", "--time", "0.5", "--max-spp", "512"});
  REQUIRE_MESSAGE(r.exitCode == 0, r.err);
  const LayeredImage img = readLayeredImage(dir.file("t.exr"));
  const std::vector<float>& n = *img.find("samples");
  double total = 0.0;
  for (float c : n) total += c;
  INFO(r.out);
  CHECK(total / double(n.size()) > 64.0);
  CHECK(*std::max_element(n.begin(), n.end()) <= 512.0f);
}

// Two adaptive renders with other seeds have other counts per pixel; merge weights each pixel by
// its own counts (as for --target-error), and the provenance lets them combine.
TEST_CASE("adaptive budget: two --adaptive renders merge by their per-pixel counts" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  for (const char* seed : {"1", "2"}) {
    CliResult r = renderOnHost(demoScene(), dir.file(std::string("s") + seed + ".exr"),
                               {"--adaptive", "--spp", "32", "--min-spp", "8", "--seed", seed}, {}, 16, 12);
    REQUIRE_MESSAGE(r.exitCode == 0, r.err);
  }
  CliResult m = runMontecl({"merge", dir.file("s1.exr"), dir.file("s2.exr"), "-o", dir.file("m.exr"), "-q"});
  REQUIRE_MESSAGE(m.exitCode == 0, m.err);
  const LayeredImage a = readLayeredImage(dir.file("s1.exr")), b = readLayeredImage(dir.file("s2.exr")),
                     merged = readLayeredImage(dir.file("m.exr"));
  const std::vector<float>&na = *a.find("samples"), &nb = *b.find("samples"), &nm = *merged.find("samples");
  const std::vector<float>&ra = *a.find("R"), &rb = *b.find("R"), &rm = *merged.find("R");
  REQUIRE(merged.find("err.R"));
  std::size_t differentCounts = 0;
  for (std::size_t p = 0; p < nm.size(); ++p) {
    CHECK(nm[p] == na[p] + nb[p]);
    differentCounts += na[p] != nb[p];
    const double expected = (double(na[p]) * ra[p] + double(nb[p]) * rb[p]) / (double(na[p]) + double(nb[p]));
    CHECK(rm[p] == doctest::Approx(expected).epsilon(1e-5));
  }
  CHECK(differentCounts > 0);
}

}  // namespace test_file_adaptive_budget
