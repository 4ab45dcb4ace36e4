// test_merge.cpp: host/image/exr_layers and `montecl merge`: named-channel EXR round trips, the
// film -> AOV conversion, the exact merge math (split per-pixel sample sets merge to the statistics
// of the whole set), and through the real command line: a render split with --first-sample and
// merged equals the single render, merged seeds have the combined error, bad inputs exit 2 with one
// line naming the file.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/provenance.h"
#include "image/film.h"
#include "stats.h"
#include "util/errors.h"

namespace test_file_merge {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
namespace fs = std::filesystem;

namespace {

// Per-pixel sample sets: samples[p] holds RGB values plus an albedo value per sample.
struct Sample {
  double rgb[3];
  double albedo;
};
using PixelSets = std::vector<std::vector<Sample>>;

// The AOV image of a set of samples per pixel, statistics computed directly in double.
LayeredImage statsImage(int w, int h, const PixelSets& sets) {
  LayeredImage im;
  im.width = w;
  im.height = h;
  std::size_t count = std::size_t(w) * h;
  std::vector<float> mean[3], var[3], n(count), albedo(count);
  for (int c = 0; c < 3; ++c) mean[c].assign(count, 0.0f), var[c].assign(count, 0.0f);
  for (std::size_t p = 0; p < count; ++p) {
    n[p] = float(sets[p].size());
    montecl_test::RunningStats s[3], a;
    for (const Sample& smp : sets[p]) {
      for (int c = 0; c < 3; ++c) s[c].add(smp.rgb[c]);
      a.add(smp.albedo);
    }
    for (int c = 0; c < 3; ++c) {
      mean[c][p] = float(s[c].mean);
      var[c][p] = float(s[c].variance());
    }
    albedo[p] = float(a.mean);
  }
  for (int c = 0; c < 3; ++c) im.set(channel::kMean[c], mean[c]);
  im.set(channel::kSamples, n);
  for (int c = 0; c < 3; ++c) im.set(channel::kVariance[c], var[c]);
  im.set("albedo.R", albedo);
  return im;
}

// Random per-pixel sample sets split into two parts (counts 0..6 in each, so n = 0 and n = 1 occur).
void makeSplitSets(int w, int h, PixelSets& a, PixelSets& b, PixelSets& all, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> count(0, 6);
  std::uniform_real_distribution<double> value(0.0, 10.0);
  std::size_t pixels = std::size_t(w) * h;
  a.assign(pixels, {});
  b.assign(pixels, {});
  all.assign(pixels, {});
  for (std::size_t p = 0; p < pixels; ++p) {
    for (PixelSets* part : {&a, &b}) {
      int k = count(rng);
      for (int i = 0; i < k; ++i) {
        Sample s{{value(rng), value(rng) * 0.1, value(rng) * 100.0}, value(rng) * 0.1};
        (*part)[p].push_back(s);
        all[p].push_back(s);
      }
    }
  }
}

void checkPlanesClose(const LayeredImage& got, const LayeredImage& want) {
  REQUIRE(got.width == want.width);
  REQUIRE(got.height == want.height);
  for (const std::string& name : want.channels) {
    const std::vector<float>* g = got.find(name);
    const std::vector<float>* w = want.find(name);
    REQUIRE_MESSAGE(g != nullptr, "missing channel " << name);
    REQUIRE(g->size() == w->size());
    double scale = 1e-12;
    for (float v : *w) scale = std::max(scale, double(std::abs(v)));
    for (std::size_t p = 0; p < w->size(); ++p) {
      INFO(name << " pixel " << p << ": got " << (*g)[p] << " want " << (*w)[p]);
      REQUIRE(std::abs((*g)[p] - (*w)[p]) <= 2e-6 * std::abs((*w)[p]) + 1e-6 * scale);
    }
  }
}

std::size_t entriesIn(const std::string& folder) {
  return std::size_t(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

void checkOneLineNaming(const CliResult& r, const std::string& file) {
  INFO("stderr: " << r.err << "\nstdout: " << r.out);
  CHECK(r.exitCode == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(file) != std::string::npos);
}

}  // namespace

TEST_CASE("merge: channel names and values round-trip through the EXR writer and reader" * doctest::test_suite("cpu")) {
  TempDir dir;
  LayeredImage im;
  im.width = 5;
  im.height = 3;
  std::vector<std::string> names{"R",        "G",        "B",        "samples", "var.R", "var.G", "var.B",
                                 "albedo.R", "albedo.G", "albedo.B", "N.X",     "N.Y",   "N.Z",   "Z"};
  for (std::size_t c = 0; c < names.size(); ++c) {
    std::vector<float> plane(15);
    for (int p = 0; p < 15; ++p) plane[p] = float(c) * 100.0f + float(p) + 0.25f;
    im.set(names[c], plane);
  }
  writeLayeredExr(dir.file("aov.exr"), im);
  CHECK(entriesIn(dir.path) == 1);  // no temporary left behind
  LayeredImage back = readLayeredImage(dir.file("aov.exr"));
  std::vector<std::string> a = im.channels, b = back.channels;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  CHECK(a == b);
  for (std::size_t c = 0; c < names.size(); ++c) CHECK(*back.find(names[c]) == *im.find(names[c]));
  CHECK_THROWS_AS(writeLayeredExr(dir.file("aov.png"), im), InputError);
  CHECK_THROWS_AS(readLayeredImage(dir.file("missing.exr")), InputError);
}

TEST_CASE("merge: takeLayersFromFilm gives mean, count and the unbiased variance of one sample" * doctest::test_suite("cpu")) {
  Film film;
  film.width = 2;
  film.height = 1;
  // pixel 0: samples 1, 2, 4 in R (G = 2x, B = 0); pixel 1: no samples
  // mean (rgb, n) and M2 = sum of squared deviations: R: mean 7/3, M2 = 21 - 49/3; G = 2R.
  const float m2R = float(21.0 - 49.0 / 3.0);
  film.mean = {glm::vec4(7.0f / 3.0f, 14.0f / 3.0f, 0, 0), glm::vec4(0)};
  film.meanLo = {glm::vec4(0), glm::vec4(0)};
  film.m2 = {glm::vec4(m2R, 4.0f * m2R, 0, 0), glm::vec4(0)};
  film.m2Lo = {glm::vec4(0), glm::vec4(0)};
  film.count = {3, 0};
  LayeredImage im = takeLayersFromFilm(film);
  CHECK((*im.find("R"))[0] == doctest::Approx(7.0 / 3.0));
  CHECK((*im.find("samples"))[0] == 3.0f);
  CHECK((*im.find("var.R"))[0] == doctest::Approx((21.0 - 49.0 / 3.0) / 2.0));
  CHECK((*im.find("var.G"))[0] == doctest::Approx(4.0 * (21.0 - 49.0 / 3.0) / 2.0));
  CHECK((*im.find("var.B"))[0] == 0.0f);
  CHECK((*im.find("R"))[1] == 0.0f);
  CHECK((*im.find("samples"))[1] == 0.0f);
}

TEST_CASE("merge: takeLayersFromFilm writes every plane from the film's accumulators, then frees them" * doctest::test_suite("cpu")) {
  // A 3x2 film with two sub-sequences per pixel and AOV sums, random contents; pixel 4 has no samples.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  Film film;
  film.width = 3;
  film.height = 2;
  const std::size_t pixels = 6, k = 2;
  auto rgb = [&] { return glm::vec4(u(rng), u(rng), u(rng), 0.0f); };
  for (std::size_t p = 0; p < pixels; ++p) {
    film.mean.push_back(rgb());
    film.meanLo.push_back(rgb() * 1e-8f);
    film.m2.push_back(rgb());
    film.m2Lo.push_back(rgb() * 1e-8f);
    film.count.push_back(p == 4 ? 0 : 2 + p);
    for (std::size_t s = 0; s < k; ++s) {
      glm::vec4 m = rgb();
      const std::uint32_t n = p == 4 ? 0u : std::uint32_t(1 + s + p);
      std::memcpy(&m.w, &n, 4);
      film.split.push_back(m);
    }
    for (int a = 0; a < MCL_AOV_VECTORS; ++a) film.aovSum.push_back(rgb());
  }
  const Film copy = film;
  const LayeredImage im = takeLayersFromFilm(film);
  auto plane = [&](const std::string& name) {
    const std::vector<float>* pl = im.find(name);
    REQUIRE(pl != nullptr);
    REQUIRE(pl->size() == pixels);
    return *pl;
  };
  // Each plane against the film's own accessors (a pixel without samples is 0 throughout).
  for (std::size_t p = 0; p < pixels; ++p) {
    CAPTURE(p);
    const bool has = copy.count[p] > 0;
    CHECK(plane("samples")[p] == float(copy.count[p]));
    for (int c = 0; c < 3; ++c) {
      CHECK(plane(channel::kMean[c])[p] == (has ? copy.mean[p][c] : 0.0f));
      CHECK(plane(channel::kVariance[c])[p] == (has ? float(copy.variance(p, c)) : 0.0f));
      const double e = has ? copy.meanVariance(p, c) : 0.0;
      CHECK(plane(channel::kMeanError[c])[p] == (std::isfinite(e) ? float(e) : 0.0f));
      for (std::size_t s = 0; s < k; ++s)
        CHECK(plane(channel::splitPrefix(s) + "." + channel::kMean[c])[p] == copy.split[k * p + s][c]);
    }
    for (std::size_t s = 0; s < k; ++s) CHECK(plane(channel::splitPrefix(s) + ".n")[p] == float(copy.splitCount(p, s)));
  }
  // Freed: mean, M2 and the sub-sequences; kept: size, counts and the AOV sums.
  CHECK(film.mean.capacity() == 0);
  CHECK(film.meanLo.capacity() == 0);
  CHECK(film.m2.capacity() == 0);
  CHECK(film.m2Lo.capacity() == 0);
  CHECK(film.split.capacity() == 0);
  CHECK(film.count == copy.count);
  CHECK(film.aovSum == copy.aovSum);
  CHECK(film.pixelCount() == pixels);
}

TEST_CASE("merge: combineStats equals the statistics of the combined sample set" * doctest::test_suite("cpu")) {
  std::mt19937 rng(11);
  std::normal_distribution<double> value(3.0, 2.0);
  std::vector<SampleStats> parts;
  montecl_test::RunningStats all;
  for (int size : {5, 1, 0, 17, 2}) {
    montecl_test::RunningStats s;
    for (int i = 0; i < size; ++i) {
      double v = value(rng);
      s.add(v);
      all.add(v);
    }
    parts.push_back({double(size), s.mean, s.variance()});
  }
  SampleStats c = combineStats(parts);
  CHECK(c.n == 25.0);
  CHECK(c.mean == doctest::Approx(all.mean).epsilon(1e-12));
  CHECK(c.variance == doctest::Approx(all.variance()).epsilon(1e-12));
  CHECK(combineStats({}).n == 0.0);
  SampleStats one = combineStats({{1.0, 4.0, 0.0}});
  CHECK(one.mean == 4.0);
  CHECK(one.variance == 0.0);
}

TEST_CASE("merge: split sample sets merge to the statistics of the whole set" * doctest::test_suite("cli sanitize")) {
  PixelSets a, b, all;
  makeSplitSets(7, 5, a, b, all, 42);
  LayeredImage ia = statsImage(7, 5, a), ib = statsImage(7, 5, b), want = statsImage(7, 5, all);

  SUBCASE("the pure function") {
    LayeredImage got = mergeLayeredImages({ia, ib}, {"a.exr", "b.exr"});
    checkPlanesClose(got, want);
  }
  SUBCASE("through montecl merge and EXR files") {
    TempDir dir;
    // Renders of one scene with disjoint samples, as montecl render would label them.
    montecl::Provenance pa{"0.14.0", "0123456789abcdef", "integrator=ao", "off", {{0, 0, 16}}}, pb = pa;
    pb.samples = {{0, 16, 32}};
    montecl::setProvenance(ia, pa);
    montecl::setProvenance(ib, pb);
    writeLayeredExr(dir.file("a.exr"), ia);
    writeLayeredExr(dir.file("b.exr"), ib);
    CliResult r = runMontecl({"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", dir.file("out.exr")});
    INFO("stderr: " << r.err);
    REQUIRE(r.exitCode == 0);
    CHECK(r.out.find("merged 2 images") != std::string::npos);
    checkPlanesClose(readLayeredImage(dir.file("out.exr")), want);
    CHECK(entriesIn(dir.path) == 3);
    // one input copies; order of inputs does not matter
    REQUIRE(runMontecl({"merge", dir.file("a.exr"), "-o", dir.file("copy.exr")}).exitCode == 0);
    checkPlanesClose(readLayeredImage(dir.file("copy.exr")), ia);
    REQUIRE(runMontecl({"merge", dir.file("b.exr"), dir.file("a.exr"), "-o", dir.file("ba.exr")}).exitCode == 0);
    checkPlanesClose(readLayeredImage(dir.file("ba.exr")), want);
  }
}

TEST_CASE("merge: three renders merge like the whole set" * doctest::test_suite("cpu")) {
  PixelSets a, b, all, c, unusedD, unusedCd;
  makeSplitSets(4, 4, a, b, all, 1);
  makeSplitSets(4, 4, c, unusedD, unusedCd, 2);  // c: a third part; all = a + b + c
  for (std::size_t p = 0; p < all.size(); ++p) all[p].insert(all[p].end(), c[p].begin(), c[p].end());
  LayeredImage got = mergeLayeredImages({statsImage(4, 4, a), statsImage(4, 4, b), statsImage(4, 4, c)}, {});
  checkPlanesClose(got, statsImage(4, 4, all));
}

TEST_CASE("merge: bad inputs exit 2 with one line naming the file" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  PixelSets a, b, all;
  makeSplitSets(4, 3, a, b, all, 5);
  writeLayeredExr(dir.file("a.exr"), statsImage(4, 3, a));
  PixelSets c, d, cd;
  makeSplitSets(3, 4, c, d, cd, 6);
  writeLayeredExr(dir.file("wrong-size.exr"), statsImage(3, 4, c));
  LayeredImage noSamples = statsImage(4, 3, b);
  LayeredImage stripped;
  stripped.width = 4;
  stripped.height = 3;
  for (std::size_t i = 0; i < noSamples.channels.size(); ++i)
    if (noSamples.channels[i] != "samples") stripped.set(noSamples.channels[i], noSamples.planes[i]);
  writeLayeredExr(dir.file("no-samples.exr"), stripped);
  dir.write("garbage.exr", "this is not an image\n");
  std::string out = dir.file("out.exr");

  checkOneLineNaming(runMontecl({"merge", dir.file("a.exr"), dir.file("wrong-size.exr"), "-o", out}),
                     "wrong-size.exr");
  checkOneLineNaming(runMontecl({"merge", dir.file("a.exr"), dir.file("no-samples.exr"), "-o", out}),
                     "no-samples.exr");
  checkOneLineNaming(runMontecl({"merge", dir.file("a.exr"), dir.file("garbage.exr"), "-o", out}), "garbage.exr");
  checkOneLineNaming(runMontecl({"merge", dir.file("a.exr"), dir.file("missing.exr"), "-o", out}), "missing.exr");
  checkOneLineNaming(runMontecl({"merge", dir.file("a.exr"), "-o", dir.file("out.png")}), "out.png");
  CHECK(!fs::exists(out));
  CHECK(!fs::exists(dir.file("out.png")));
  CHECK(entriesIn(dir.path) == 4);  // the inputs only: no partial or temporary outputs
  CHECK(runMontecl({"merge", "-o", out}).exitCode == 2);  // no inputs
}

TEST_CASE("a render split with --first-sample and merged equals the single render" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  REQUIRE(runMontecl(demoRenderArgs(dir.file("all.exr"), 16, 0)).exitCode == 0);
  REQUIRE(runMontecl(demoRenderArgs(dir.file("a.exr"), 6, 0)).exitCode == 0);
  REQUIRE(runMontecl(demoRenderArgs(dir.file("b.exr"), 10, 6)).exitCode == 0);
  CliResult merged = runMontecl({"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", dir.file("m.exr")});
  INFO(merged.err);
  REQUIRE(merged.exitCode == 0);

  montecl::LayeredImage all = montecl::readLayeredImage(dir.file("all.exr"));
  montecl::LayeredImage m = montecl::readLayeredImage(dir.file("m.exr"));
  montecl::LayeredImage a = montecl::readLayeredImage(dir.file("a.exr"));
  REQUIRE(all.width == 24);
  REQUIRE(m.width == all.width);
  REQUIRE(m.height == all.height);
  for (const char* name : {"R", "G", "B", "samples", "var.R"}) {
    CAPTURE(name);
    REQUIRE(all.find(name) != nullptr);
    REQUIRE(m.find(name) != nullptr);
    const std::vector<float>& x = *all.find(name);
    const std::vector<float>& y = *m.find(name);
    double worst = 0.0;
    for (std::size_t p = 0; p < x.size(); ++p)
      worst = std::max(worst, std::fabs(double(x[p]) - y[p]) / std::max(1e-3, std::fabs(double(x[p]))));
    CHECK(worst < 1e-4);
  }
  CHECK((*all.find("samples"))[0] == 16.0f);
  CHECK((*a.find("samples"))[0] == 6.0f);
  // The split really rendered different samples: the halves differ from each other.
  const std::vector<float>& ar = *a.find("R");
  // Keep the image alive: a reference into the temporary readLayeredImage() returns would dangle
  // (ASan: heap-use-after-free).
  const montecl::LayeredImage b = montecl::readLayeredImage(dir.file("b.exr"));
  REQUIRE(b.find("R") != nullptr);
  const std::vector<float>& br = *b.find("R");
  CHECK(ar != br);
}

TEST_CASE("merging renders with different seeds has the error of the combined sample count" * doctest::test_suite("cli sanitize")) {
  // Two 8 spp renders (seeds 1, 2) merged, against an independent 512 spp render (seed 3): per
  // pixel, z = (merged - reference) / sqrt(var/16 + var_ref/512) from the files' own variances.
  TempDir dir;
  auto args = [&](const std::string& out, int spp, int seed) {
    return std::vector<std::string>{"render", demoScene(), "-o", out, "--width", "24", "--height", "16", "--spp",
                                    std::to_string(spp), "--seed", std::to_string(seed), "--ao-sampling",
                                    "uniform", "--sampler", "independent", "-q"};  // var/n: i.i.d. samples
  };
  REQUIRE(runMontecl(args(dir.file("s1.exr"), 8, 1)).exitCode == 0);
  REQUIRE(runMontecl(args(dir.file("s2.exr"), 8, 2)).exitCode == 0);
  REQUIRE(runMontecl(args(dir.file("ref.exr"), 512, 3)).exitCode == 0);
  REQUIRE(runMontecl({"merge", dir.file("s1.exr"), dir.file("s2.exr"), "-o", dir.file("m.exr"), "-q"}).exitCode == 0);
  montecl::LayeredImage m = montecl::readLayeredImage(dir.file("m.exr"));
  montecl::LayeredImage ref = montecl::readLayeredImage(dir.file("ref.exr"));
  const auto& mr = *m.find("G");
  const auto& mv = *m.find("var.G");
  const auto& mn = *m.find("samples");
  const auto& rr = *ref.find("G");
  const auto& rv = *ref.find("var.G");
  int compared = 0, outliers = 0;
  double zSum = 0.0, zSq = 0.0;
  for (std::size_t p = 0; p < mr.size(); ++p) {
    REQUIRE(mn[p] == 16.0f);
    double var = mv[p] / 16.0 + rv[p] / 512.0;
    if (var <= 0.0) continue;  // e.g. background: both exact
    double z = (mr[p] - rr[p]) / std::sqrt(var);
    ++compared;
    zSum += z;
    zSq += z * z;
    outliers += std::fabs(z) > 4.0;
  }
  double meanZ = zSum / compared, rmsZ = std::sqrt(zSq / compared);
  INFO("compared " << compared << ", mean z " << meanZ << ", rms z " << rmsZ);
  REQUIRE(compared > 100);
  CHECK(outliers <= 2);
  CHECK(std::fabs(meanZ) < 0.3);
  CHECK(rmsZ > 0.7);  // an error far below the combined count's would mean the variance is wrong
  CHECK(rmsZ < 1.4);
}

}  // namespace test_file_merge
