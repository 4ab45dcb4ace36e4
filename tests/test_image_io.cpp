// test_image_io.cpp: through the real command line, a render split with --first-sample into
// two runs and combined by `montecl merge` equals one run of all the samples (float rounding),
// and its EXR carries the sample count and variance channels.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <filesystem>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/png_write.h"

using namespace montecl_test;

namespace {

const std::string kScene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";

std::vector<std::string> renderArgs(const std::string& out, int spp, int first) {
  return {"render", kScene, "-o", out, "--width", "24", "--height", "16", "--spp", std::to_string(spp),
          "--first-sample", std::to_string(first), "--ao-sampling", "uniform", "-q"};
}

// Renders the same samples to dir/x<ext> and dir/x.exr; returns the EXR.
montecl::LayeredImage renderWithExr(const TempDir& dir, const std::string& ext) {
  std::vector<std::string> args = renderArgs(dir.file("x" + ext), 4, 0);
  REQUIRE(runMontecl(args).exitCode == 0);
  args[3] = dir.file("x.exr");
  REQUIRE(runMontecl(args).exitCode == 0);
  return montecl::readLayeredImage(dir.file("x.exr"));
}

}  // namespace

TEST_CASE("a render split with --first-sample and merged equals the single render") {
  TempDir dir;
  REQUIRE(runMontecl(renderArgs(dir.file("all.exr"), 16, 0)).exitCode == 0);
  REQUIRE(runMontecl(renderArgs(dir.file("a.exr"), 6, 0)).exitCode == 0);
  REQUIRE(runMontecl(renderArgs(dir.file("b.exr"), 10, 6)).exitCode == 0);
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
  const std::vector<float>& br = *montecl::readLayeredImage(dir.file("b.exr")).find("R");
  CHECK(ar != br);
}

TEST_CASE("a .pfm render is a little-endian float map with the image's size and values") {
  TempDir dir;
  montecl::LayeredImage exr = renderWithExr(dir, ".pfm");
  std::ifstream in(dir.file("x.pfm"), std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  float scale = 0;
  in >> magic >> w >> h >> scale;
  in.get();
  CHECK(magic == "PF");
  CHECK(w == 24);
  CHECK(h == 16);
  CHECK(scale < 0.0f);
  std::vector<float> data(std::size_t(w) * h * 3);
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * 4));
  REQUIRE(in);
  // PFM rows run bottom to top; EXR rows top to bottom.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      REQUIRE(data[(std::size_t(h - 1 - y) * w + x) * 3 + 1] == (*exr.find("G"))[std::size_t(y) * w + x]);
}

TEST_CASE("a .png render is the sRGB encoding of the same render's EXR means, 8 bits, clamped") {
  TempDir dir;
  montecl::LayeredImage exr = renderWithExr(dir, ".png");
  montecl::LayeredImage png = montecl::readLayeredImage(dir.file("x.png"));
  REQUIRE(png.width == 24);
  REQUIRE(png.height == 16);
  REQUIRE(png.channels.size() == 3);
  int nonBlack = 0;
  for (int c = 0; c < 3; ++c)
    for (std::size_t p = 0; p < png.pixelCount(); ++p) {
      int want = montecl::linearToSrgb8((*exr.find(montecl::channel::kMean[c]))[p]);
      REQUIRE(std::lround(png.planes[c][p] * 255.0f) == want);
      nonBlack += want > 0;
    }
  CHECK(nonBlack > 0);
}

TEST_CASE("linearToSrgb8 follows the sRGB curve: linear toe, 2.4 power, clamping, NaN to 0") {
  CHECK(montecl::linearToSrgb8(0.0f) == 0);
  CHECK(montecl::linearToSrgb8(-1.0f) == 0);
  CHECK(montecl::linearToSrgb8(NAN) == 0);
  CHECK(montecl::linearToSrgb8(1.0f) == 255);
  CHECK(montecl::linearToSrgb8(INFINITY) == 255);
  CHECK(montecl::linearToSrgb8(0.002f) == 7);    // 12.92 * 0.002 * 255 = 6.59
  CHECK(montecl::linearToSrgb8(0.5f) == 188);    // (1.055 * 0.5^(1/2.4) - 0.055) * 255 = 187.52
  CHECK(montecl::linearToSrgb8(0.22f) == 129);   // (1.055 * 0.22^(1/2.4) - 0.055) * 255 = 129.13
}

TEST_CASE("an EXR render without the OpenImageIO module fails with one line and leaves no file") {
  TempDir dir;
  CliResult r = runMontecl(renderArgs(dir.file("x.exr"), 1, 0), {"MONTECL_IMAGE_PLUGIN=" + dir.file("missing.so")});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find(dir.file("x.exr")) != std::string::npos);
  CHECK(r.err.find("missing.so") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator{}) == 0);
  // PNG output does not need the module.
  CHECK(runMontecl(renderArgs(dir.file("x.png"), 1, 0), {"MONTECL_IMAGE_PLUGIN=" + dir.file("missing.so")}).exitCode == 0);
}

TEST_CASE("merging renders with different seeds has the error of the combined sample count") {
  // Two 8 spp renders (seeds 1, 2) merged, against an independent 512 spp render (seed 3): per
  // pixel, z = (merged - reference) / sqrt(var/16 + var_ref/512) from the files' own variances.
  TempDir dir;
  auto args = [&](const std::string& out, int spp, int seed) {
    return std::vector<std::string>{"render", kScene, "-o", out, "--width", "24", "--height", "16", "--spp",
                                    std::to_string(spp), "--seed", std::to_string(seed), "--ao-sampling",
                                    "uniform", "-q"};
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
