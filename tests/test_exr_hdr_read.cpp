// test_exr_hdr_read.cpp: montecl's own EXR (OpenEXR) and Radiance HDR (stb_image) readers against
// OpenImageIO's decode of the same small files, written here: EXR RGB / RGBA / Y in half and float,
// mixed, tiled with mip levels, multi-part, channel names in every order rule OpenImageIO applies,
// string attributes, and montecl's own layered AOV EXR from a render; HDR run-length encoded
// (written by OpenImageIO) and flat (written here, every mantissa at several exponents).
// Bit-identical planes, the same channel names and order, pixel type and attributes. A corrupt or
// truncated EXR / HDR is one InputError naming the file, and an EXR- or HDR-lit render and
// `montecl merge` need no OpenImageIO module.
#include <doctest/doctest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <ImfTiledOutputFile.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/image_read.h"
#include "image/oiio_loader.h"
#include "util/errors.h"

namespace test_file_exr_hdr_read {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// The value of channel c of pixel (x, y): negatives, fractions, large, tiny, an infinity.
float sampleValue(int x, int y, int c) {
  if (x == 1 && y == 1 && c == 0) return std::numeric_limits<float>::infinity();
  if (x == 2 && y == 0) return 1e-6f * float(c + 1);  // a half subnormal
  return (float(x * 37 + y * 11 + c * 101) - 200.0f) * 0.0173f * (c == 2 ? 400.0f : 1.0f);
}

struct ExrChannelSpec {
  std::string name;
  Imf::PixelType type;
};

// A w x h EXR (scanlines, or tiles with mip levels) with the given channels (in this order in the
// header: OpenEXR sorts them by name), sampleValue per channel index, and string attributes.
void writeExr(const std::string& path, int w, int h, const std::vector<ExrChannelSpec>& chans, bool tiled = false,
              const std::vector<std::pair<std::string, std::string>>& attributes = {}) {
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& c : chans) header.channels().insert(c.name, Imf::Channel(c.type));
  for (const auto& [k, v] : attributes) header.insert(k, Imf::StringAttribute(v));
  std::vector<std::vector<half>> halves(chans.size());
  std::vector<std::vector<float>> floats(chans.size());
  Imf::FrameBuffer frame;
  for (std::size_t i = 0; i < chans.size(); ++i) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float v = sampleValue(x, y, int(i));
        halves[i].push_back(half(v));
        floats[i].push_back(v);
      }
    if (chans[i].type == Imf::HALF)
      frame.insert(chans[i].name, Imf::Slice(Imf::HALF, (char*)halves[i].data(), sizeof(half), sizeof(half) * w));
    else
      frame.insert(chans[i].name, Imf::Slice(Imf::FLOAT, (char*)floats[i].data(), sizeof(float), sizeof(float) * w));
  }
  if (tiled) {
    header.setTileDescription(Imf::TileDescription(4, 4, Imf::MIPMAP_LEVELS));
    Imf::TiledOutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    for (int l = 0; l < out.numLevels(); ++l) out.writeTiles(0, out.numXTiles(l) - 1, 0, out.numYTiles(l) - 1, l);
    return;
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(h);
}

// Float planes compared by their bits (a NaN or -0 too).
bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// montecl's reader and OpenImageIO's give the same image, bit for bit, from the file and from memory.
void checkSameAsOiio(const std::string& path) {
  CAPTURE(path);
  REQUIRE(readsWithoutOiio(path));
  const LayeredImage own = readImageFile(path);
  const LayeredImage oiio = oiioRead(path);
  CHECK(own.width == oiio.width);
  CHECK(own.height == oiio.height);
  CHECK(own.pixelType == oiio.pixelType);
  const auto joined = [](const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += n + " ";
    return s;
  };
  CHECK(joined(own.channels) == joined(oiio.channels));
  CHECK(own.attributes == oiio.attributes);
  REQUIRE(own.planes.size() == oiio.planes.size());
  for (std::size_t c = 0; c < own.planes.size(); ++c) {
    CAPTURE(own.channels[c]);
    CHECK(sameBits(own.planes[c], oiio.planes[c]));
  }
  const std::string bytes = readAll(path);
  const LayeredImage mem = readImageMemory(path, std::vector<unsigned char>(bytes.begin(), bytes.end()));
  CHECK(mem.channels == own.channels);
  CHECK(mem.planes == own.planes);
}

std::string readErrorOf(const std::string& path) {
  try {
    readLayeredImage(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A flat (not run-length encoded) Radiance file of w x h RGBE pixels rgbe(x, y) -> 4 bytes.
template <class F>
void writeFlatHdr(const std::string& path, int w, int h, F rgbe) {
  std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::array<unsigned char, 4> p = rgbe(x, y);
      s.append(reinterpret_cast<const char*>(p.data()), 4);
    }
  std::ofstream(path, std::ios::binary) << s;
}

}  // namespace

TEST_CASE("exr read: montecl's EXR reader gives OpenImageIO's planes, channel order and attributes" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  using C = ExrChannelSpec;
  const Imf::PixelType H = Imf::HALF, F = Imf::FLOAT;
  writeExr(dir.file("rgb-half.exr"), 7, 5, {{"R", H}, {"G", H}, {"B", H}});
  writeExr(dir.file("rgba-half.exr"), 7, 5, {{"R", H}, {"G", H}, {"B", H}, {"A", H}});
  writeExr(dir.file("rgb-float.exr"), 7, 5, {{"R", F}, {"G", F}, {"B", F}});
  writeExr(dir.file("rgba-float.exr"), 7, 5, {{"R", F}, {"G", F}, {"B", F}, {"A", F}});
  writeExr(dir.file("y-half.exr"), 7, 5, {{"Y", H}});
  writeExr(dir.file("mixed.exr"), 7, 5, {{"R", H}, {"G", F}, {"B", H}, {"A", F}});
  writeExr(dir.file("tiled-mip.exr"), 9, 6, {{"R", H}, {"G", H}, {"B", H}, {"A", H}}, true);
  // Every rule of OpenImageIO's order: layers by name (none first), reserved names (any case) in
  // their order within a layer, the rest by name; a dot in a layer's name.
  writeExr(dir.file("order.exr"), 5, 3,
           {{"zz", F},      {"Z", F},       {"alpha", H},   {"b", F},       {"Red", F},     {"g", H},
            {"Depth", F},   {"Y", F},       {"foo", F},     {"var.R", F},   {"var.B", F},   {"var.G", F},
            {"N.X", F},     {"N.Z", F},     {"N.Y", F},     {"a.b.G", F},   {"a.b.R", F},   {"a.b.extra", F},
            {"split0.n", F}, {"split0.R", F}, {"split10.B", F}, {"split2.G", F}, {"imag", F},    {"real", F},
            {"Zback", F},   {"AR", F},      {"RA", F}});
  // A layer with X and Y or Z (a position, a normal) orders X Y Z before alpha; X alone does not.
  writeExr(dir.file("order-xyz.exr"), 5, 3,
           {{"Zback", F}, {"Depth", F}, {"A", F}, {"Z", F}, {"Y", F}, {"X", F}, {"real", F}, {"R", F}, {"P.z", F},
            {"P.x", F}, {"P.A", F}, {"P.Depth", F}, {"Q.A", F}, {"Q.X", F}, {"S.X", F}, {"S.A", F}, {"S.B", F}});
  // Luminance-chroma: OpenImageIO converts it to RGB, montecl hands it to OpenImageIO.
  writeExr(dir.file("luminance-chroma.exr"), 6, 4, {{"Y", H}, {"RY", H}, {"BY", H}});
  writeExr(dir.file("attributes.exr"), 4, 4, {{"R", F}, {"G", F}, {"B", F}}, false,
           {{"montecl:scene", "abc123"}, {"montecl:settings", "{\"spp\": 4}"}, {"comments", "not montecl's"}});
  // A montecl render: every AOV layer, the sobol sub-sequences, the provenance attributes.
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n");
  const CliResult r = runMontecl({"render", dir.file("quad.obj"), "-o", dir.file("render.exr"), "--width", "8",
                                  "--height", "6", "--spp", "4", "-q", "--aov", "all"});
  REQUIRE(r.exitCode == 0);
  // A two-part file: OpenImageIO and montecl read part 0.
  {
    Imf::Header a(3, 2), b(3, 2);
    a.channels().insert("R", Imf::Channel(Imf::FLOAT));
    b.channels().insert("G", Imf::Channel(Imf::HALF));
    a.setName("first");
    b.setName("second");
    a.setType(Imf::SCANLINEIMAGE);
    b.setType(Imf::SCANLINEIMAGE);
    Imf::MultiPartOutputFile out(dir.file("two-part.exr").c_str(), std::vector<Imf::Header>{a, b}.data(), 2);
    std::vector<float> r6 = {1, 2, 3, 4, 5, 6};
    std::vector<half> g6(6, half(0.5f));
    Imf::OutputPart p0(out, 0), p1(out, 1);
    Imf::FrameBuffer f0, f1;
    f0.insert("R", Imf::Slice(Imf::FLOAT, (char*)r6.data(), sizeof(float), sizeof(float) * 3));
    f1.insert("G", Imf::Slice(Imf::HALF, (char*)g6.data(), sizeof(half), sizeof(half) * 3));
    p0.setFrameBuffer(f0);
    p0.writePixels(2);
    p1.setFrameBuffer(f1);
    p1.writePixels(2);
  }
  for (const std::string& f : dir.entries())
    if (std::filesystem::path(f).extension() == ".exr") checkSameAsOiio(dir.file(f));
  const LayeredImage render = readLayeredImage(dir.file("render.exr"));
  CHECK(render.find("samples"));
  CHECK(render.find("var.R"));
  CHECK(render.attributes.size() >= 3);
}

TEST_CASE("exr read: a corrupt or truncated EXR is one InputError naming the file; 1000 mutants never crash" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeExr(dir.file("good.exr"), 16, 16, {{"R", Imf::HALF}, {"G", Imf::HALF}, {"B", Imf::FLOAT}});
  const std::string good = readAll(dir.file("good.exr"));
  dir.write("truncated.exr", good.substr(0, good.size() * 2 / 3));
  dir.write("header-only.exr", good.substr(0, 100));
  std::string flipped = good;
  for (std::size_t i = good.size() - 40; i < good.size(); ++i) flipped[i] = char(flipped[i] ^ 0x5a);  // pixel data
  dir.write("flipped.exr", flipped);
  dir.write("text.exr", "this is not an EXR");
  dir.write("empty.exr", "");
  for (const std::string name : {"truncated.exr", "header-only.exr", "flipped.exr", "text.exr", "empty.exr"}) {
    CAPTURE(name);
    const std::string why = readErrorOf(dir.file(name));
    CHECK(why.rfind(dir.file(name) + ": cannot read image: ", 0) == 0);
    CHECK(why.find('\n') == std::string::npos);
  }
  const ImageSizeCheck refuse = [](int w, int h, int c) {
    return "declares " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c);
  };
  CHECK_THROWS_WITH_AS(readImageFile(dir.file("good.exr"), refuse), doctest::Contains("cannot read image: declares 16x16x3"),
                       InputError);
  CHECK(readImageSize(dir.file("good.exr")).width == 16);
  std::uint32_t state = 777u;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  int decoded = 0, refused = 0;
  for (int i = 0; i < 1000; ++i) {
    std::string m = good;
    const int edits = 1 + int(next() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = next() % m.size();
      switch (next() % 3) {
        case 0: m[at] = char(next()); break;
        case 1: m.resize(std::max<std::size_t>(at, 1)); break;
        default: m.insert(at, std::string(1 + next() % 8, char(next()))); break;
      }
    }
    try {
      readImageMemory("mutant.exr", std::vector<unsigned char>(m.begin(), m.end()));
      ++decoded;
    } catch (const InputError& e) {
      INFO("mutant " << i << ": " << std::string(e.what()));
      CHECK(std::string(e.what()).rfind("mutant.exr: cannot read image: ", 0) == 0);
      CHECK(std::string(e.what()).find('\n') == std::string::npos);
      ++refused;
    }
  }
  CHECK(decoded + refused == 1000);
  CHECK(refused > 0);
}

TEST_CASE("hdr read: montecl's Radiance reader gives OpenImageIO's floats, run-length encoded and flat; mutants end" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  // Run-length encoded, as OpenImageIO writes a row 8 to 32767 pixels wide.
  LayeredImage im;
  im.width = 37;
  im.height = 9;
  for (int c = 0; c < 3; ++c) {
    std::vector<float> plane;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        plane.push_back(y == 4 ? 0.25f : std::abs(sampleValue(x, y, c)) * std::pow(10.0f, float(y - 4)));
    im.set(c == 0 ? "R" : c == 1 ? "G" : "B", plane);
  }
  oiioWrite(dir.file("rle.hdr"), dir.file("rle.hdr"), im);
  // Flat: every mantissa (with a zero exponent byte: black) at exponents from tiny to huge.
  const int exps[] = {0, 1, 60, 127, 128, 129, 136, 200, 254, 255};
  writeFlatHdr(dir.file("flat.hdr"), 256, 10, [&](int x, int y) {
    return std::array<unsigned char, 4>{(unsigned char)x, (unsigned char)(255 - x), (unsigned char)((x * 7) % 256),
                                        (unsigned char)exps[y]};
  });
  for (const std::string f : {"rle.hdr", "flat.hdr"}) checkSameAsOiio(dir.file(f));
  // The exact value: mantissa times 2^(exponent - 136), 0 for a zero exponent byte.
  const LayeredImage flat = readImageFile(dir.file("flat.hdr"));
  REQUIRE(flat.channels == std::vector<std::string>{"R", "G", "B"});
  CHECK(flat.pixelType == "float");
  int exact = 0;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 256; ++x) {
      const float expected = exps[y] == 0 ? 0.0f : float(std::ldexp(double(x), exps[y] - 136));
      exact += flat.planes[0][std::size_t(y * 256 + x)] == expected;
    }
  CHECK(exact == 2560);
  // A truncated or damaged file: one line naming it.
  const std::string rle = readAll(dir.file("rle.hdr")), flatBytes = readAll(dir.file("flat.hdr"));
  dir.write("truncated-rle.hdr", rle.substr(0, rle.size() * 2 / 3));
  dir.write("truncated-flat.hdr", flatBytes.substr(0, flatBytes.size() - 5));
  dir.write("no-size.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n");
  dir.write("text.hdr", "this is not a Radiance file");
  for (const std::string name : {"truncated-rle.hdr", "truncated-flat.hdr", "no-size.hdr", "text.hdr"}) {
    CAPTURE(name);
    const std::string why = readErrorOf(dir.file(name));
    CHECK(why.rfind(dir.file(name) + ": cannot read image: ", 0) == 0);
    CHECK(why.find('\n') == std::string::npos);
  }
  const ImageSizeCheck refuse = [](int w, int h, int) { return "declares " + std::to_string(w) + "x" + std::to_string(h); };
  CHECK_THROWS_WITH_AS(readImageFile(dir.file("rle.hdr"), refuse), doctest::Contains("cannot read image: declares 37x9"),
                       InputError);
  CHECK(readImageSize(dir.file("flat.hdr")).width == 256);
  // Mutants of both encodings from memory: each decodes or is one InputError, and each ends (a
  // zero run-length count past the end would spin stb_image forever).
  std::uint32_t state = 4242u;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (const std::string& seed : {rle, flatBytes}) {
    int decoded = 0, refused = 0;
    for (int i = 0; i < 500; ++i) {
      std::string m = seed;
      const int edits = 1 + int(next() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = next() % m.size();
        switch (next() % 3) {
          case 0: m[at] = char(next()); break;
          case 1: m.resize(std::max<std::size_t>(at, 1)); break;
          default: m.insert(at, std::string(1 + next() % 8, char(next()))); break;
        }
      }
      try {
        readImageMemory("mutant.hdr", std::vector<unsigned char>(m.begin(), m.end()));
        ++decoded;
      } catch (const InputError& e) {
        CHECK(std::string(e.what()).rfind("mutant.hdr: cannot read image: ", 0) == 0);
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
        ++refused;
      }
    }
    CHECK(decoded + refused == 500);
    CHECK(refused > 0);
  }
}

TEST_CASE("exr/hdr read: EXR- and HDR-lit renders and merge need no OpenImageIO module; a corrupt map is exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeExr(dir.file("sky.exr"), 16, 8, {{"R", Imf::HALF}, {"G", Imf::HALF}, {"B", Imf::HALF}});
  writeFlatHdr(dir.file("sky.hdr"), 16, 8, [](int x, int y) {
    return std::array<unsigned char, 4>{(unsigned char)(100 + x), (unsigned char)(120 + y), 140, 128};
  });
  // sampleValue has negatives and an infinity: an environment map must not.
  LayeredImage sky = readImageFile(dir.file("sky.exr"));
  for (auto& plane : sky.planes)
    for (float& v : plane) v = std::isfinite(v) ? std::abs(v) : 1.0f;
  writeLayeredExr(dir.file("sky.exr"), sky);
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n");
  const std::vector<std::string> noModule = {"MONTECL_IMAGE_PLUGIN=" + dir.file("no-such-module.so")};
  for (const std::string map : {"sky.exr", "sky.hdr"}) {
    CAPTURE(map);
    dir.write("scene.json", std::string(R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 6},
      "meshes": [{"file": "quad.obj"}], "environment": {"file": ")") + map +
                                R"("}, "render": {"integrator": "path", "spp": 2}})");
    for (const char* out : {"a.exr", "b.exr"}) {
      const CliResult r = runMontecl({"render", dir.file("scene.json"), "-o", dir.file(out), "-q", "--device", "host",
                                      "--seed", out[0] == 'a' ? "1" : "2"},
                                     noModule);
      CHECK(r.exitCode == 0);
      CHECK(r.err.find("OpenImageIO") == std::string::npos);
    }
    const CliResult m = runMontecl({"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", dir.file("m.exr"), "-q"}, noModule);
    CHECK(m.exitCode == 0);
    CHECK(m.err.find("OpenImageIO") == std::string::npos);
    std::filesystem::remove(dir.file("m.exr"));
  }
  for (const std::string map : {"sky.exr", "sky.hdr"}) {
    CAPTURE(map);
    const std::string bytes = readAll(dir.file(map));
    dir.write(map, bytes.substr(0, bytes.size() / 2));
    dir.write("scene.json", std::string(R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 6},
      "meshes": [{"file": "quad.obj"}], "environment": {"file": ")") + map +
                                R"("}, "render": {"spp": 1}})");
    const CliResult bad = runMontecl({"render", dir.file("scene.json"), "-o", dir.file("bad.png"), "-q", "--device", "host"},
                                     noModule);
    CHECK(bad.exitCode == 2);
    CHECK(bad.err.find(std::string(map) + ": cannot read image") != std::string::npos);
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(dir.file("bad.png")));
  }
}

}  // namespace test_file_exr_hdr_read
