// test_gltf_images.cpp: glTF images held inside the file (a .glb bufferView, a data URI) decode from
// memory: the same model as .gltf with an external PNG, .gltf with a data URI and .glb with the PNG
// in its BIN chunk renders bit-identically through the command line, and textured (not the bare
// base colour); an embedded image in a format montecl does not read is one line, exit 2.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "mesh_files.h"
#include "test_images.h"

namespace test_file_gltf_images {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
using nlohmann::json;

namespace {

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void putU32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xffu);
}

// The tent (with UVs) whose material's baseColorTexture is image 0, described by `image`.
json texturedTent(const json& image) {
  json g = json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 1.0f, "tent.bin"));
  g["images"] = json::array({image});
  g["textures"] = json::array({json{{"source", 0}}});
  g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  return g;
}

// A GLB of glTF JSON g whose buffer 0 is `bin` (g's buffer 0 loses its uri).
std::string glb(json g, std::string bin) {
  g["buffers"][0].erase("uri");
  while (bin.size() % 4) bin += '\0';
  g["buffers"][0]["byteLength"] = bin.size();
  std::string text = g.dump();
  while (text.size() % 4) text += ' ';
  std::string out = "glTF";
  putU32(out, 2);
  putU32(out, std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  putU32(out, std::uint32_t(text.size()));
  out += "JSON" + text;
  putU32(out, std::uint32_t(bin.size()));
  out += std::string("BIN\0", 4) + bin;
  return out;
}

// The albedo AOV of `model` (16 x 16, 1 spp, AO), or empty planes when the render failed.
std::vector<std::vector<float>> albedoOf(const TempDir& dir, const std::string& model) {
  const std::string out = dir.file(model + ".exr");
  const CliResult r = runMontecl({"render", dir.file(model), "-o", out, "--width", "16", "--height", "16", "--spp", "1",
                                  "--integrator", "ao", "--aov", "albedo", "-q", "--overwrite"});
  INFO(model << ": " << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("embedded") == std::string::npos);  // nothing skipped, nothing warned
  if (r.exitCode != 0) return {};
  const montecl::LayeredImage im = montecl::readLayeredImage(out);
  std::vector<std::vector<float>> planes;
  for (const char* c : {"albedo.R", "albedo.G", "albedo.B"}) planes.push_back(*im.find(c));
  return planes;
}

}  // namespace

TEST_CASE("glTF: a texture as a file, a data URI or a GLB bufferView renders bit-identically, textured" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  montecl_test::writeImage8(dir.file("tex.png"), 8, 8, 3, [](int x, int y, int c) { return (x * 32 + y * 7 + c * 80) % 256; });
  const std::string png = fileBytes(dir.file("tex.png"));
  dir.write("tent.bin", montecl_test::gltfBuffer(montecl_test::tentMesh()));
  dir.write("file.gltf", texturedTent({{"uri", "tex.png"}}).dump());
  dir.write("data.gltf", texturedTent({{"uri", "data:image/png;base64," + montecl_test::base64(png)}}).dump());
  // The GLB: the mesh's buffer, then the PNG (4-byte aligned) as bufferView k.
  std::string bin = montecl_test::gltfBuffer(montecl_test::tentMesh());
  while (bin.size() % 4) bin += '\0';
  json g = texturedTent({});
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", png.size()}});
  g["images"][0] = {{"bufferView", g["bufferViews"].size() - 1}, {"mimeType", "image/png"}};
  dir.write("tent.glb", glb(g, bin + png));

  const auto file = albedoOf(dir, "file.gltf");
  REQUIRE(file.size() == 3);
  // Textured: the albedo varies over the tent (a bare base colour of 1 would be one value).
  float lo = 1e9f, hi = -1e9f;
  for (float v : file[0]) {
    if (v > 0.0f) lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  CHECK(hi > lo + 0.1f);
  CHECK(albedoOf(dir, "data.gltf") == file);
  CHECK(albedoOf(dir, "tent.glb") == file);

  // An embedded image in a format montecl does not read: one line naming the file and the image.
  g["images"][0]["mimeType"] = "image/ktx2";
  g["bufferViews"].back()["byteLength"] = 16;
  dir.write("ktx.glb", glb(g, bin + std::string(16, 'k')));
  const CliResult bad = runMontecl({"render", dir.file("ktx.glb"), "-o", dir.file("ktx.png"), "-q"});
  INFO(bad.err);
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find(dir.file("ktx.glb") + ": images[0]: embedded image of type 'image/ktx2'") != std::string::npos);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_FALSE(std::filesystem::exists(dir.file("ktx.png")));

  // An image bufferView that runs past its buffer (tinygltf does not check it): one line, never read.
  g["images"][0]["mimeType"] = "image/png";
  g["bufferViews"].back()["byteLength"] = 4096;
  dir.write("short.glb", glb(g, bin + png));
  const CliResult shortView = runMontecl({"render", dir.file("short.glb"), "-o", dir.file("short.png"), "-q"});
  INFO(shortView.err);
  CHECK(shortView.exitCode == 2);
  CHECK(shortView.err.find(dir.file("short.glb") + ": images[0]: bufferView " + std::to_string(g["bufferViews"].size() - 1) +
                           " runs past the end of its buffer") != std::string::npos);
  CHECK(std::count(shortView.err.begin(), shortView.err.end(), '\n') == 1);
}

TEST_CASE("glTF: a bare textured .glb renders coloured by default (lit by the default sky), with no warning; "
          "--integrator ao stays grey" *
          doctest::test_suite("cli")) {
  TempDir dir;
  // Red and blue halves: a grey image (AO, or an untextured base colour) has R == B everywhere.
  montecl_test::writeImage8(dir.file("tex.png"), 8, 8, 3, [](int x, int, int c) { return c == (x < 4 ? 0 : 2) ? 230 : 20; });
  const std::string png = fileBytes(dir.file("tex.png"));
  std::string bin = montecl_test::gltfBuffer(montecl_test::tentMesh());
  while (bin.size() % 4) bin += '\0';
  json g = texturedTent({});
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", png.size()}});
  g["images"][0] = {{"bufferView", g["bufferViews"].size() - 1}, {"mimeType", "image/png"}};
  dir.write("tent.glb", glb(g, bin + png));
  const auto render = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> a = {"render", dir.file("tent.glb"), "-o", dir.file(out), "--width", "16", "--height",
                                  "16", "--spp", "4", "--aov", "albedo", "--overwrite"};
    a.insert(a.end(), extra.begin(), extra.end());
    const CliResult r = runMontecl(a);
    INFO(r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.err.find("warning") == std::string::npos);
    return montecl::readLayeredImage(dir.file(out));
  };
  // How far the image is from grey, and whether the model's pixels are lit at all.
  const auto colourfulness = [](const montecl::LayeredImage& im, const char* r, const char* b) {
    float most = 0.0f;
    const std::vector<float>& R = *im.find(r);
    const std::vector<float>& B = *im.find(b);
    for (std::size_t i = 0; i < R.size(); ++i) most = std::max(most, std::fabs(R[i] - B[i]));
    return most;
  };
  const montecl::LayeredImage lit = render("lit.exr", {});
  CHECK(colourfulness(lit, "R", "B") > 0.2f);
  CHECK(colourfulness(lit, "albedo.R", "albedo.B") > 0.5f);
  // The albedo AOV is the texture as AO's albedo AOV reads it; AO's own image is grey.
  const montecl::LayeredImage ao = render("ao.exr", {"--integrator", "ao"});
  CHECK(*ao.find("albedo.R") == *lit.find("albedo.R"));
  CHECK(*ao.find("albedo.B") == *lit.find("albedo.B"));
  CHECK(colourfulness(ao, "R", "B") == 0.0f);
}

}  // namespace test_file_gltf_images
