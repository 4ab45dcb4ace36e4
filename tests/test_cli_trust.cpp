// test_cli_trust.cpp: through the real command line, inputs that used to cost gigabytes or render
// wrong values with exit 0 are refused up front with one line, exit 2 and no output: an image
// file declaring more pixels than the texture budget keeps or than the memory check allows
// (textures, environment maps, merge inputs; refused from the header, before decoding); albedo
// textures with NaN, negative or over-half-float texels (the environment map's rule); PLY float
// indices that are fractional, NaN or out of range; merge inputs holding NaN or inf, a data window
// off the origin, or a merge output that is one of its inputs; glTF negative byte offsets, projective
// node matrices, a string emissiveStrength, %00 in a URI, GLB version 1 and node instancing past the
// memory check. And after --resume the summary says what the image holds.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>

#include "cli_checks.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/image_io.h"
#include "mesh_files.h"
#include "test_images.h"

namespace test_file_cli_trust {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, checkRefused, ... (fixtures/cli_runner.h, cli_checks.h)
namespace fs = std::filesystem;

namespace {

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string bigEndian(std::uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string pngChunk(const std::string& type, const std::string& data) {
  return bigEndian(std::uint32_t(data.size())) + type + data + bigEndian(crc32(type + data));
}

// A 65-byte PNG whose header declares side x side RGBA pixels (8 bits), with an empty zlib stream
// as its only IDAT: decoding it would allocate the whole declared image first.
std::string tinyPng(std::uint32_t side) {
  const std::string ihdr = bigEndian(side) + bigEndian(side) + std::string("\x08\x06\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) +
         pngChunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) + pngChunk("IEND", "");
}

// A quad with uvs whose material's map_Kd is `texture`.
std::string writeTexturedQuad(const TempDir& dir, const std::string& texture) {
  dir.write("quad.obj", "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                        "usemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  dir.write("quad.mtl", "newmtl m\nKd 1 1 1\nmap_Kd " + texture + "\n");
  return dir.file("quad.obj");
}

CliResult render(const std::string& scene, const std::string& out, std::vector<std::string> extra = {},
                 const std::vector<std::string>& env = {}) {
  extra.insert(extra.begin(), {"--integrator", "direct"});  // an integrator that reads colour textures (AO loads none)
  return renderOnHost(scene, out, extra, env);
}

}  // namespace

TEST_CASE("cli: a texture declaring more texels than --texture-budget keeps is refused from its header" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = writeTexturedQuad(dir, "tex.png"), out = dir.file("out.png");
  // 256x256 half-float RGBA texels are 512 KiB: over a 0.25 MiB budget (it rendered, levels dropped).
  montecl_test::writeImage8(dir.file("tex.png"), 256, 256, 3, [](int x, int y, int c) { return (x + y + c) % 256; });
  checkRefused(render(scene, out, {"--texture-budget", "0.25"}), out,
               {"tex.png: material 'm' map_Kd", "256x256", "--texture-budget"});
  CHECK(render(scene, out, {"--texture-budget", "0.5"}).exitCode == 0);  // 512 KiB fits
  fs::remove(out);
  // 65 bytes declaring 16384x16384 (2 GiB of texels) under the default 1 GiB budget.
  dir.write("tex.png", tinyPng(16384));
  checkRefused(render(scene, out), out, {"tex.png: material 'm' map_Kd", "16384x16384", "--texture-budget"});
}

TEST_CASE("cli: an environment map or merge input too large for the memory check is refused before decoding" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string out = dir.file("out.png");
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
    "meshes": [{"file": "quad.obj"}], "environment": {"file": "sky.exr"}})");
  // 512x256 RGB: about 6 MB to decode and tabulate, over a machine declared to have 4 MB (an 8x8
  // render itself fits in that).
  montecl::writeRgbImage(dir.file("sky.exr"), 512, 256, std::vector<float>(512 * 256 * 3, 0.5f));
  checkRefused(render(dir.file("scene.json"), out, {}, {"MONTECL_MEMORY_LIMIT=4000000"}), out,
               {"environment.file", "sky.exr", "512x256", "this machine has"});
  CHECK(render(dir.file("scene.json"), out, {}, {"MONTECL_MEMORY_LIMIT=40000000"}).exitCode == 0);

  // Merge inputs: 64x64 with 4 channels, about 200 KB each to decode and merge; 100 KB declared.
  montecl::LayeredImage im;
  im.width = im.height = 64;
  for (const char* name : {"R", "G", "B", "samples"}) im.set(name, std::vector<float>(64 * 64, 1.0f));
  montecl::writeLayeredExr(dir.file("a.exr"), im);
  montecl::writeLayeredExr(dir.file("b.exr"), im);
  const std::vector<std::string> merge{"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", dir.file("m.exr"),
                                       "--force", "-q"};
  checkRefused(runMontecl(merge, {"MONTECL_MEMORY_LIMIT=100000"}), dir.file("m.exr"), {"a.exr", "64x64"});
  CHECK(runMontecl(merge, {"MONTECL_MEMORY_LIMIT=10000000"}).exitCode == 0);
}

TEST_CASE("cli: an albedo texture with NaN, negative or over-half-float texels is refused before rendering" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = writeTexturedQuad(dir, "tex.exr"), out = dir.file("out.png");
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), -0.5f, 70000.0f, std::numeric_limits<float>::infinity()}) {
    CAPTURE(bad);
    std::vector<float> rgb(4 * 4 * 3, 0.5f);
    rgb[(2 * 4 + 1) * 3 + 1] = bad;  // pixel (1, 2), green
    montecl::writeRgbImage(dir.file("tex.exr"), 4, 4, rgb);
    checkRefused(render(scene, out), out, {"tex.exr: material 'm' map_Kd", "pixel (1, 2)"});
  }
  montecl::writeRgbImage(dir.file("tex.exr"), 4, 4, std::vector<float>(4 * 4 * 3, 65504.0f));  // the half maximum
  CHECK(render(scene, out).exitCode == 0);
}

TEST_CASE("cli: a PLY float index that is fractional, NaN or out of range is one line naming the row and the number" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n"
                           "0 0 0\n1 0 0\n0 1 0\n";
  const std::string out = dir.file("out.png");
  const std::pair<std::string, std::string> cases[] = {
      {"3 0 1.5 2\n", "element 'face' row 0: vertex index 1.5 is not a whole number"},
      {"3 0 nan 2\n", "element 'face' row 0: vertex index nan out of range (3 vertices)"},
      {"3 0 1 1e30\n", "element 'face' row 0: vertex index 1e+30 out of range"},
      {"3 0 1 -inf\n", "element 'face' row 0: vertex index -inf out of range"},
  };
  for (const auto& row : cases) {
    const auto& face = std::get<0>(row);
    const auto& needle = std::get<1>(row);
    CAPTURE(face);
    dir.write("bad.ply", head + face);
    checkRefused(render(dir.file("bad.ply"), out), out, {dir.file("bad.ply") + ": " + needle});
  }
  // An integer list told a fraction, and one whose fraction std::to_string printed as 0.000000.
  std::string intHead = head;
  intHead.replace(intHead.find("uchar float"), 11, "uchar int");
  dir.write("bad.ply", intHead + "3 0 1e-7 2\n");
  checkRefused(render(dir.file("bad.ply"), out), out, {"element 'face' row 0: expected an integer, got 1e-07"});
  dir.write("good.ply", head + "3 0 1 2\n");  // whole floats are indices
  CHECK(render(dir.file("good.ply"), out).exitCode == 0);
}

TEST_CASE("cli: the summary after --resume reports the samples the image holds, not only this run's" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  // Both runs stop at the time limit, so the checkpoint is partial and the resumed run adds to it.
  const auto args = [&](const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> v{"render", montecl_test::demoScene(), "-o", dir.file(out), "--width", "8", "--height",
                               "8", "--spp", "1000000", "--time", "0.05", "--device", "host", "-q"};
    v.insert(v.end(), extra.begin(), extra.end());
    return v;
  };
  const CliResult a = runMontecl(args("a.exr", {"--checkpoint", dir.file("c.ckpt"), "--checkpoint-every", "0.000001"}));
  REQUIRE_MESSAGE(a.exitCode == 0, a.err);
  const CliResult b = runMontecl(args("b.exr", {"--resume", dir.file("c.ckpt")}));
  REQUIRE_MESSAGE(b.exitCode == 0, b.err);
  const montecl::LayeredImage image = montecl::readLayeredImage(dir.file("b.exr"));
  const std::vector<float>& n = *image.find("samples");
  const auto [lo, hi] = std::minmax_element(n.begin(), n.end());
  double sum = 0.0;
  for (float v : n) sum += v;
  char expected[128];
  if (*lo == *hi) std::snprintf(expected, sizeof expected, "; the image now holds %.0f spp", double(*lo));
  else
    std::snprintf(expected, sizeof expected, "; the image now holds %.1f spp on average (%.0f..%.0f per pixel)",
                  sum / double(n.size()), double(*lo), double(*hi));
  INFO("stdout: " << b.out);
  CHECK(b.out.find(expected) != std::string::npos);
  CHECK(a.out.find("the image now holds") == std::string::npos);  // a fresh render's spp are the image's
}

namespace {

// A w x h EXR of R, G, B, samples (all 1) whose data window starts at (x0, y0) (display window at
// the origin), written through OpenEXR directly (montecl's writer always puts it at the origin).
void writeOffsetExr(const std::string& path, int w, int h, int x0, int y0) {
  Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(w - 1, h - 1)),
                     Imath::Box2i(Imath::V2i(x0, y0), Imath::V2i(x0 + w - 1, y0 + h - 1)));
  std::vector<float> ones(std::size_t(w) * h, 1.0f);
  Imf::FrameBuffer frame;
  char* base = reinterpret_cast<char*>(ones.data()) - (std::ptrdiff_t(y0) * w + x0) * std::ptrdiff_t(sizeof(float));
  for (const char* name : {"R", "G", "B", "samples"}) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    frame.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(w)));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(h);
}

montecl::LayeredImage onesImage(int w, int h) {
  montecl::LayeredImage im;
  im.width = w;
  im.height = h;
  for (const char* name : {"R", "G", "B", "samples"}) im.set(name, std::vector<float>(std::size_t(w) * h, 1.0f));
  return im;
}

}  // namespace

TEST_CASE("cli: merge refuses NaN or infinite inputs, a data window off the origin and an output that is an input" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  montecl::writeLayeredExr(dir.file("a.exr"), onesImage(4, 3));
  const auto merge = [&](const std::string& b, const std::string& out) {
    return runMontecl({"merge", dir.file("a.exr"), dir.file(b), "-o", dir.file(out), "--force", "-q"});
  };
  REQUIRE(merge("a.exr", "m.exr").exitCode == 0);  // --force: the same file twice is allowed
  fs::remove(dir.file("m.exr"));
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    montecl::LayeredImage im = onesImage(4, 3);
    (*im.find(bad == bad ? "samples" : "G"))[2 * 4 + 1] = bad;  // pixel (1, 2)
    montecl::writeLayeredExr(dir.file("bad.exr"), im);
    checkRefused(merge("bad.exr", "m.exr"), dir.file("m.exr"),
                 {dir.file("bad.exr") + ": pixel (1, 2) channel '" + (bad == bad ? "samples" : "G") + "' is not finite"});
  }
  writeOffsetExr(dir.file("offset.exr"), 4, 3, 3, 2);
  checkRefused(merge("offset.exr", "m.exr"), dir.file("m.exr"), {"offset.exr", "data window starts at (3, 2)"});
  const std::string before = montecl_test::readAll(dir.file("a.exr"));
  const CliResult self = runMontecl({"merge", dir.file("a.exr"), dir.file("a.exr"), "-o", dir.file("a.exr"), "--force"});
  CHECK(self.exitCode == 2);
  CHECK(oneLine(self.err));
  CHECK(self.err.find("the output is an input") != std::string::npos);
  CHECK(montecl_test::readAll(dir.file("a.exr")) == before);
}

TEST_CASE("cli: glTF negative byteOffset, projective matrix, string emissiveStrength, %00 URI, GLB 1 and runaway instancing are refused" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const montecl_test::MeshData mesh = montecl_test::tentMesh();
  const nlohmann::json good = nlohmann::json::parse(montecl_test::gltfText(mesh, 0.5f, ""));
  const std::string out = dir.file("out.png");
  REQUIRE(render((dir.write("good.gltf", good.dump()), dir.file("good.gltf")), out).exitCode == 0);
  fs::remove(out);
  struct Case {
    std::function<void(nlohmann::json&)> edit;
    std::string key;
  } cases[] = {
      {[](nlohmann::json& j) { j["bufferViews"][0]["byteOffset"] = -4; }, "bufferViews[0].byteOffset"},
      {[](nlohmann::json& j) { j["accessors"][0]["byteOffset"] = -12; }, "accessors[0].byteOffset"},
      {[](nlohmann::json& j) {
         j["nodes"][0] = {{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1}}};
       }, "nodes[0].matrix"},
      {[](nlohmann::json& j) {
         j["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = "5";
       }, "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"},
      {[](nlohmann::json& j) { j["images"] = {{{"uri", "tex%00.png"}}}; }, "images[0].uri"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.key);
    nlohmann::json j = good;
    c.edit(j);
    dir.write("bad.gltf", j.dump());
    checkRefused(render(dir.file("bad.gltf"), out), out, {dir.file("bad.gltf") + ": " + c.key});
  }
  std::string glb = montecl_test::glbBytes(mesh, 0.5f);
  glb[4] = 1;  // version 1
  dir.write("v1.glb", glb);
  checkRefused(render(dir.file("v1.glb"), out), out, {dir.file("v1.glb") + ": header", "GLB version 1"});
  // 10000 nodes placing the 4-triangle mesh, emitting (so flattened into copies: the emitter table
  // is world space): 40000 triangles, megabytes, on a machine declared to have 2 MB (the 8x8 image
  // fits in it); 10 nodes load. Not emitting, the mesh is read once and placed 10000 times: the
  // placements (about 4.8 MB) are refused at 2 MB, naming the instances, and load in 8 MB.
  for (int nodes : {10, 10000}) {
    nlohmann::json j = good;
    j["materials"][0]["emissiveFactor"] = {1, 1, 1};
    j["nodes"] = nlohmann::json::array();
    j["scenes"][0]["nodes"] = nlohmann::json::array();
    for (int i = 0; i < nodes; ++i) {
      j["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, -0.001 * i}}});
      j["scenes"][0]["nodes"].push_back(i);
    }
    dir.write("many.gltf", j.dump());
    const CliResult r = render(dir.file("many.gltf"), out, {}, {"MONTECL_MEMORY_LIMIT=2000000"});
    if (nodes == 10) {
      CHECK_MESSAGE(r.exitCode == 0, r.err);
      fs::remove(out);
    } else {
      checkRefused(r, out, {dir.file("many.gltf") + ": nodes[", "triangles", "this machine has"});
      j["materials"][0].erase("emissiveFactor");
      dir.write("many.gltf", j.dump());
      checkRefused(render(dir.file("many.gltf"), out, {}, {"MONTECL_MEMORY_LIMIT=2000000"}), out,
                   {dir.file("many.gltf") + ": nodes[", "10000 instances", "this machine has"});
      const CliResult kept = render(dir.file("many.gltf"), out, {}, {"MONTECL_MEMORY_LIMIT=8000000"});
      CHECK_MESSAGE(kept.exitCode == 0, kept.err);
      fs::remove(out);
    }
  }
}

}  // namespace test_file_cli_trust
