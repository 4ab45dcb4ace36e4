// test_image_io.cpp: host/image writers through the real command line: PFM layout, PNG as the sRGB
// encoding of the EXR means (and linearToSrgb8), and EXR output failing cleanly without the
// OpenImageIO module.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <filesystem>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/png_write.h"

namespace test_file_image_io {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// Renders the same samples to dir/x<ext> and dir/x.exr; returns the EXR.
montecl::LayeredImage renderWithExr(const TempDir& dir, const std::string& ext) {
  std::vector<std::string> args = demoRenderArgs(dir.file("x" + ext), 4, 0);
  REQUIRE(runMontecl(args).exitCode == 0);
  args[3] = dir.file("x.exr");
  REQUIRE(runMontecl(args).exitCode == 0);
  return montecl::readLayeredImage(dir.file("x.exr"));
}

}  // namespace

TEST_CASE("a .pfm render is a little-endian float map with the image's size and values" * doctest::test_suite("cli sanitize")) {
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

TEST_CASE("a .png render is the sRGB encoding of the same render's EXR means, 8 bits, clamped" * doctest::test_suite("cli sanitize")) {
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

TEST_CASE("linearToSrgb8 follows the sRGB curve: linear toe, 2.4 power, clamping, NaN to 0" * doctest::test_suite("cpu")) {
  CHECK(montecl::linearToSrgb8(0.0f) == 0);
  CHECK(montecl::linearToSrgb8(-1.0f) == 0);
  CHECK(montecl::linearToSrgb8(NAN) == 0);
  CHECK(montecl::linearToSrgb8(1.0f) == 255);
  CHECK(montecl::linearToSrgb8(INFINITY) == 255);
  CHECK(montecl::linearToSrgb8(0.002f) == 7);    // 12.92 * 0.002 * 255 = 6.59
  CHECK(montecl::linearToSrgb8(0.5f) == 188);    // (1.055 * 0.5^(1/2.4) - 0.055) * 255 = 187.52
  CHECK(montecl::linearToSrgb8(0.22f) == 129);   // (1.055 * 0.22^(1/2.4) - 0.055) * 255 = 129.13
}

TEST_CASE("EXR output needs no OpenImageIO module; reading an image without it fails with one line" * doctest::test_suite("cli sanitize")) {
  // EXR files are written with OpenEXR itself (image/exr_writer.h): loading the OpenImageIO
  // module for a write cost ~120 MiB of resident memory. EXR reads use OpenEXR too
  // (image/exr_read.h); other formats (a TIFF here) still go through the module.
  TempDir dir;
  const std::string missing = "MONTECL_IMAGE_PLUGIN=" + dir.file("missing.so");
  REQUIRE(runMontecl(demoRenderArgs(dir.file("x.exr"), 1, 0), {missing}).exitCode == 0);
  const montecl::LayeredImage x = montecl::readLayeredImage(dir.file("x.exr"));
  CHECK(x.width > 0);
  CliResult ok = runMontecl({"merge", dir.file("x.exr"), dir.file("x.exr"), "-o", dir.file("m.exr"), "--force", "-q"}, {missing});
  CHECK(ok.exitCode == 0);
  CHECK(std::filesystem::exists(dir.file("m.exr")));
  montecl::oiioWrite(dir.file("x.tif"), dir.file("x.tif"), x);  // with the module, in this process
  CliResult r = runMontecl({"merge", dir.file("x.tif"), dir.file("x.tif"), "-o", dir.file("t.exr")}, {missing});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find(dir.file("x.tif")) != std::string::npos);
  CHECK(r.err.find("missing.so") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(!std::filesystem::exists(dir.file("t.exr")));
  // PNG output does not need the module either.
  CHECK(runMontecl(demoRenderArgs(dir.file("x.png"), 1, 0), {missing}).exitCode == 0);
}

}  // namespace test_file_image_io
