// test_image_read.cpp: montecl's own PNG (libpng) and JPEG (libjpeg-turbo) readers against
// OpenImageIO's decode of the same small files, written here with libpng and libjpeg: 8- and 16-bit,
// grey, grey + alpha, RGB, RGBA, palette (with and without tRNS), 1-, 2- and 4-bit grey, interlaced;
// JPEG grey and RGB at two chroma subsamplings. Bit-identical planes, same channel names and pixel
// type. A corrupt or truncated PNG / JPEG is one InputError naming the file (from memory too), and
// a render of a PNG- and JPEG-textured scene needs no OpenImageIO module at all.
#include <doctest/doctest.h>

#include <png.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <jpeglib.h>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/image_read.h"
#include "image/oiio_loader.h"
#include "util/errors.h"

namespace test_file_image_read {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// A PNG of colorType and bitDepth whose sample s of pixel (x, y) is f(x, y, s) (masked to the bit
// depth; palette images: the index), written row by row with libpng.
template <class F>
void writePngKind(const std::string& path, int w, int h, int colorType, int bitDepth, F f, bool interlace = false,
                  bool trns = false) {
  FILE* fp = std::fopen(path.c_str(), "wb");
  REQUIRE(fp);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  REQUIRE(!setjmp(png_jmpbuf(png)));
  png_init_io(png, fp);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), bitDepth, colorType,
               interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette(16);
  std::vector<png_byte> alpha(16);
  for (int i = 0; i < 16; ++i) {
    palette[std::size_t(i)] = png_color{png_byte(i * 17), png_byte(255 - i * 13), png_byte((i * 71) % 256)};
    alpha[std::size_t(i)] = png_byte(i * 16 + 3);
  }
  if (colorType == PNG_COLOR_TYPE_PALETTE) {
    png_set_PLTE(png, info, palette.data(), 16);
    if (trns) png_set_tRNS(png, info, alpha.data(), 16, nullptr);
  }
  png_write_info(png, info);
  const int samples = colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_PALETTE ? 1
                      : colorType == PNG_COLOR_TYPE_GRAY_ALPHA                               ? 2
                      : colorType == PNG_COLOR_TYPE_RGB                                      ? 3
                                                                                             : 4;
  const int passes = png_set_interlace_handling(png);
  const unsigned mask = bitDepth == 16 ? 0xffffu : (1u << bitDepth) - 1u;
  std::vector<std::vector<png_byte>> rows(std::size_t(h), std::vector<png_byte>(std::size_t(w * samples * 2 + 8), 0));
  for (int y = 0; y < h; ++y) {
    std::vector<png_byte>& row = rows[std::size_t(y)];
    for (int x = 0; x < w; ++x)
      for (int s = 0; s < samples; ++s) {
        const unsigned v = unsigned(f(x, y, s)) & mask;
        const int i = x * samples + s;
        if (bitDepth == 16) {
          row[std::size_t(2 * i)] = png_byte(v >> 8);
          row[std::size_t(2 * i + 1)] = png_byte(v & 0xff);
        } else if (bitDepth == 8) {
          row[std::size_t(i)] = png_byte(v);
        } else {  // packed, most significant bits first
          const int bit = i * bitDepth;
          row[std::size_t(bit / 8)] |= png_byte(v << (8 - bitDepth - bit % 8));
        }
      }
  }
  for (int p = 0; p < passes; ++p)
    for (int y = 0; y < h; ++y) png_write_row(png, rows[std::size_t(y)].data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(fp);
}

// A JPEG of 1 or 3 components, quality 90, with chroma subsampled by hs x vs (1 x 1: none).
void writeJpegKind(const std::string& path, int w, int h, int components, int hs, int vs) {
  FILE* fp = std::fopen(path.c_str(), "wb");
  REQUIRE(fp);
  jpeg_compress_struct c{};
  jpeg_error_mgr err{};
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  jpeg_stdio_dest(&c, fp);
  c.image_width = JDIMENSION(w);
  c.image_height = JDIMENSION(h);
  c.input_components = components;
  c.in_color_space = components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 90, TRUE);
  if (components == 3) {
    c.comp_info[0].h_samp_factor = hs;
    c.comp_info[0].v_samp_factor = vs;
  }
  jpeg_start_compress(&c, TRUE);
  std::vector<JSAMPLE> row(std::size_t(w * components));
  while (c.next_scanline < c.image_height) {
    const int y = int(c.next_scanline);
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < components; ++k) row[std::size_t(x * components + k)] = JSAMPLE((x * 37 + y * 11 + k * 90 + x * y) % 256);
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&c, &r, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::fclose(fp);
}

// montecl's reader and OpenImageIO's give the same image, bit for bit.
void checkSameAsOiio(const std::string& path) {
  CAPTURE(path);
  REQUIRE(readsWithoutOiio(path));
  const LayeredImage own = readImageFile(path);
  const LayeredImage oiio = oiioRead(path);
  CHECK(own.width == oiio.width);
  CHECK(own.height == oiio.height);
  CHECK(own.pixelType == oiio.pixelType);
  CHECK(own.channels == oiio.channels);
  REQUIRE(own.planes.size() == oiio.planes.size());
  for (std::size_t c = 0; c < own.planes.size(); ++c) {
    CAPTURE(c);
    CHECK(own.planes[c] == oiio.planes[c]);
  }
  // From memory too (an image inside a .glb).
  const std::string bytes = readAll(path);
  const LayeredImage mem = readImageMemory(path, std::vector<unsigned char>(bytes.begin(), bytes.end()));
  CHECK(mem.planes == own.planes);
}

std::string readErrorOf(const std::string& path) {
  try {
    readImageFile(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("image read: montecl's PNG reader gives OpenImageIO's texels for every PNG kind" * doctest::test_suite("cpu")) {
  TempDir dir;
  const auto code = [](int x, int y, int s) { return x * 53 + y * 19 + s * 77 + x * y * 5; };
  const auto wide = [](int x, int y, int s) { return x * 4099 + y * 257 + s * 9001 + x * y * 131; };
  writePngKind(dir.file("rgb8.png"), 13, 7, PNG_COLOR_TYPE_RGB, 8, code);
  writePngKind(dir.file("rgba8.png"), 13, 7, PNG_COLOR_TYPE_RGB_ALPHA, 8, code);
  writePngKind(dir.file("grey8.png"), 13, 7, PNG_COLOR_TYPE_GRAY, 8, code);
  writePngKind(dir.file("greyalpha8.png"), 13, 7, PNG_COLOR_TYPE_GRAY_ALPHA, 8, code);
  writePngKind(dir.file("rgb16.png"), 13, 7, PNG_COLOR_TYPE_RGB, 16, wide);
  writePngKind(dir.file("rgba16.png"), 13, 7, PNG_COLOR_TYPE_RGB_ALPHA, 16, wide);
  writePngKind(dir.file("grey16.png"), 13, 7, PNG_COLOR_TYPE_GRAY, 16, wide);
  writePngKind(dir.file("greyalpha16.png"), 13, 7, PNG_COLOR_TYPE_GRAY_ALPHA, 16, wide);
  writePngKind(dir.file("palette.png"), 13, 7, PNG_COLOR_TYPE_PALETTE, 8, [](int x, int y, int) { return (x + y) % 16; });
  writePngKind(dir.file("palette-trns.png"), 13, 7, PNG_COLOR_TYPE_PALETTE, 4, [](int x, int y, int) { return (x * 3 + y) % 16; },
               false, true);
  writePngKind(dir.file("grey1.png"), 13, 7, PNG_COLOR_TYPE_GRAY, 1, code);
  writePngKind(dir.file("grey2.png"), 13, 7, PNG_COLOR_TYPE_GRAY, 2, code);
  writePngKind(dir.file("grey4.png"), 13, 7, PNG_COLOR_TYPE_GRAY, 4, code);
  writePngKind(dir.file("interlaced.png"), 13, 7, PNG_COLOR_TYPE_RGB_ALPHA, 8, code, true);
  // Every code of 8 and 16 bits once (the code -> float conversion, value by value).
  writePngKind(dir.file("codes8.png"), 256, 1, PNG_COLOR_TYPE_GRAY, 8, [](int x, int, int) { return x; });
  writePngKind(dir.file("codes16.png"), 256, 256, PNG_COLOR_TYPE_GRAY, 16, [](int x, int y, int) { return y * 256 + x; });
  for (const std::string& f : dir.entries()) checkSameAsOiio(dir.file(f));
}

TEST_CASE("image read: montecl's JPEG reader gives OpenImageIO's pixels (grey, RGB 4:4:4 and 4:2:0)" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeJpegKind(dir.file("grey.jpg"), 21, 11, 1, 1, 1);
  writeJpegKind(dir.file("rgb444.jpeg"), 21, 11, 3, 1, 1);
  writeJpegKind(dir.file("rgb420.JPG"), 21, 11, 3, 2, 2);
  for (const std::string& f : dir.entries()) checkSameAsOiio(dir.file(f));
}

TEST_CASE("image read: the signature picks the reader: a PNG named .jpg and a JPEG named .png read as they are" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writePngKind(dir.file("png.jpg"), 9, 5, PNG_COLOR_TYPE_RGB_ALPHA, 8, [](int x, int y, int s) { return x * 31 + y * 7 + s; });
  writeJpegKind(dir.file("jpeg.png"), 9, 5, 3, 1, 1);
  writePngKind(dir.file("png.tga"), 9, 5, PNG_COLOR_TYPE_GRAY, 8, [](int x, int y, int) { return x * 20 + y; });
  for (const std::string& f : dir.entries()) checkSameAsOiio(dir.file(f));
  // In memory (a .glb's image named by its mime type) the same.
  const std::string bytes = readAll(dir.file("png.jpg"));
  const LayeredImage mem = readImageMemory("image.jpg", std::vector<unsigned char>(bytes.begin(), bytes.end()));
  CHECK(mem.width == 9);
  CHECK(mem.planes == readImageFile(dir.file("png.jpg")).planes);
}

TEST_CASE("image read: a corrupt or truncated PNG or JPEG is one InputError naming the file" * doctest::test_suite("cpu")) {
  TempDir dir;
  writePngKind(dir.file("good.png"), 32, 32, PNG_COLOR_TYPE_RGB, 8, [](int x, int y, int s) { return x * y + s; });
  writeJpegKind(dir.file("good.jpg"), 32, 32, 3, 2, 2);
  const std::string png = readAll(dir.file("good.png")), jpg = readAll(dir.file("good.jpg"));
  dir.write("truncated.png", png.substr(0, png.size() / 2));
  dir.write("truncated.jpg", jpg.substr(0, jpg.size() / 2));
  std::string flipped = png;
  for (std::size_t i = 40; i < 60 && i < flipped.size(); ++i) flipped[i] = char(flipped[i] ^ 0x5a);  // IDAT, CRC
  dir.write("flipped.png", flipped);
  dir.write("text.png", "this is not a PNG");
  dir.write("text.jpg", "this is not a JPEG");
  dir.write("empty.png", "");
  for (const char* name : {"truncated.png", "truncated.jpg", "flipped.png", "text.png", "text.jpg", "empty.png"}) {
    CAPTURE(name);
    const std::string why = readErrorOf(dir.file(name));
    CHECK(why.rfind(dir.file(name) + ": cannot read image: ", 0) == 0);
    CHECK(why.find('\n') == std::string::npos);
  }
  // From memory: the error names the image as the caller calls it.
  const std::vector<unsigned char> half(png.begin(), png.begin() + std::ptrdiff_t(png.size() / 2));
  CHECK_THROWS_WITH_AS(readImageMemory("model.glb image 0.png", half), doctest::Contains("model.glb image 0.png: cannot read image"),
                       InputError);
  // The declared size is refused before any pixel is decoded, with the caller's reason.
  const ImageSizeCheck refuse = [](int w, int h, int) { return "declares " + std::to_string(w) + "x" + std::to_string(h); };
  CHECK_THROWS_WITH_AS(readImageFile(dir.file("good.png"), refuse), doctest::Contains("cannot read image: declares 32x32"),
                       InputError);
  CHECK_THROWS_WITH_AS(readImageFile(dir.file("good.jpg"), refuse), doctest::Contains("cannot read image: declares 32x32"),
                       InputError);
}

TEST_CASE("image read: a PNG- and JPEG-textured render needs no OpenImageIO module; a corrupt texture is exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("quad.obj",
            "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "usemtl m\nf 1/1 2/2 3/3\nusemtl n\nf 1/1 3/3 4/4\n");
  dir.write("quad.mtl", "newmtl m\nKd 1 1 1\nmap_Kd tex.png\nmap_d tex.png\nnewmtl n\nKd 1 1 1\nmap_Kd tex.jpg\n");
  writePngKind(dir.file("tex.png"), 16, 16, PNG_COLOR_TYPE_RGB_ALPHA, 8, [](int x, int y, int s) { return s == 3 ? (x % 4 ? 255 : 0) : x * y + s * 40; });
  writeJpegKind(dir.file("tex.jpg"), 16, 16, 3, 2, 2);
  // No module where montecl would look: any read through OpenImageIO would fail.
  const std::vector<std::string> noModule = {"MONTECL_IMAGE_PLUGIN=" + dir.file("no-such-module.so")};
  for (const char* out : {"out.png", "out.exr"}) {
    CAPTURE(out);
    const CliResult r = runMontecl({"render", dir.file("quad.obj"), "-o", dir.file(out), "--width", "16", "--height", "16",
                                    "--spp", "1", "-q", "--integrator", "direct"},
                                   noModule);
    CHECK(r.exitCode == 0);
    CHECK(r.err.find("OpenImageIO") == std::string::npos);
    CHECK(std::filesystem::exists(dir.file(out)));
  }
  const std::string jpg = readAll(dir.file("tex.jpg"));
  dir.write("tex.jpg", jpg.substr(0, jpg.size() / 3));
  const CliResult bad = runMontecl({"render", dir.file("quad.obj"), "-o", dir.file("bad.png"), "--width", "16", "--height",
                                    "16", "--spp", "1", "-q", "--integrator", "direct"},
                                   noModule);
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("tex.jpg: material 'n' map_Kd: cannot read image") != std::string::npos);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK(!std::filesystem::exists(dir.file("bad.png")));
}

TEST_CASE("image read: 3000 mutated PNGs and JPEGs each decode or are one InputError, never a crash" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writePngKind(dir.file("seed.png"), 24, 9, PNG_COLOR_TYPE_PALETTE, 4, [](int x, int y, int) { return x + y; }, true, true);
  writePngKind(dir.file("seed16.png"), 9, 9, PNG_COLOR_TYPE_RGB_ALPHA, 16, [](int x, int y, int s) { return x * 5000 + y * 7 + s; });
  writeJpegKind(dir.file("seed.jpg"), 24, 17, 3, 2, 2);
  std::uint32_t state = 12345u;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (const char* seedName : {"seed.png", "seed16.png", "seed.jpg"}) {
    const std::string seed = readAll(dir.file(seedName));
    const std::string name = "mutant" + std::filesystem::path(seedName).extension().string();  // picks the reader
    int decoded = 0, refused = 0;
    for (int i = 0; i < 1000; ++i) {
      std::string m = seed;
      const int edits = 1 + int(next() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = next() % m.size();
        switch (next() % 3) {
          case 0: m[at] = char(next()); break;                      // one byte
          case 1: m.resize(std::max<std::size_t>(at, 1)); break;    // truncated
          default: m.insert(at, std::string(1 + next() % 8, char(next()))); break;  // bytes inserted
        }
      }
      try {
        readImageMemory(name, std::vector<unsigned char>(m.begin(), m.end()));
        ++decoded;
      } catch (const InputError& e) {
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
        ++refused;
      }
    }
    CAPTURE(seedName);
    CHECK(decoded + refused == 1000);
    CHECK(refused > 0);
  }
}

}  // namespace test_file_image_read
