// test_texture_sampling.cpp: how glTF textures are read, through the loader and the kernels (the
// default OpenCL device): KHR_texture_transform (a transformed checker's albedo AOV is the texel
// the transform names, and equals the pre-transformed image's), sampler wrap modes per axis
// (repeat, clamp to edge, mirrored repeat: the expected texel per pixel), TEXCOORD_1 named by
// texCoord or by the extension's texCoord, KHR_materials_unlit (the base colour as radiance, zero
// variance), and bad values as one line naming the key, exit 2 (the command line).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "test_images.h"
#include "texture/mip_chain.h"

namespace test_file_texture_sampling {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;
using nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;

// 8-bit value of cell (i, j) (j = 0 the top row) of a 4 x 4 cell texture.
int cellValue(int i, int j, int c) { return (37 * i + 71 * j + 53 * c + 40) % 256; }

// A cell texture of 4 x 4 cells of 16 x 16 pixels.
void writeCells(const std::string& path) {
  writeImage8(path, 64, 64, 3, [](int x, int y, int c) { return cellValue(x / 16, y / 16, c); });
}

template <class T>
std::string bytesOf(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// A glTF quad filling [-1, 1]^2 at z = 0 (facing +z) with TEXCOORD_0 = uv0 and, when given,
// TEXCOORD_1 = uv1 (4 vertices: bottom-left, bottom-right, top-right, top-left; glTF's UVs, v
// down); material is its one material, textures / samplers / images as given.
// colour: COLOR_0's bytes (4 elements of type colourType, components of colourComponent), or none.
json quadGltf(const std::vector<float>& uv0, const std::vector<float>& uv1, const json& material,
              const std::string& colour = "", int colourComponent = 5126, const char* colourType = "VEC3") {
  const std::vector<float> pos = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::vector<std::uint16_t> idx = {0, 1, 2, 0, 2, 3, 0, 0};  // padded to 4 bytes
  std::string buf = bytesOf(pos) + bytesOf(idx) + bytesOf(uv0) + bytesOf(uv1);
  const std::size_t colourAt = buf.size();
  buf += colour;
  json g;
  g["asset"] = {{"version", "2.0"}};
  g["buffers"] = {{{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}}};
  g["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                      {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}},
                      {{"buffer", 0}, {"byteOffset", 64}, {"byteLength", 32}}};
  g["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                     {"min", {-1, -1, 0}}, {"max", {1, 1, 0}}},
                    {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
                    {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}};
  json attributes = {{"POSITION", 0}, {"TEXCOORD_0", 2}};
  if (!uv1.empty()) {
    g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}});
    g["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
    attributes["TEXCOORD_1"] = 3;
  }
  if (!colour.empty()) {
    g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", colourAt}, {"byteLength", colour.size()}});
    g["accessors"].push_back({{"bufferView", g["bufferViews"].size() - 1}, {"componentType", colourComponent},
                              {"count", 4}, {"type", colourType}, {"normalized", colourComponent != 5126}});
    attributes["COLOR_0"] = g["accessors"].size() - 1;
  }
  g["meshes"] = {{{"primitives", {{{"attributes", attributes}, {"indices", 1}, {"material", 0}}}}}};
  g["nodes"] = {{{"mesh", 0}}};
  g["scenes"] = {{{"nodes", {0}}}};
  g["materials"] = json::array({material});  // not {material}: clang makes that a copy of the object
  return g;
}

// UVs spanning [u0, u1] left to right and [v0, v1] top to bottom (glTF's v).
std::vector<float> uvRect(float u0, float u1, float v0, float v1) { return {u0, v1, u1, v1, u1, v0, u0, v0}; }

// A base-colour-textured material (texture 0) with the textureInfo's extra keys.
json texturedMaterial(const json& info = json::object()) {
  json t = info;
  t["index"] = 0;
  return {{"pbrMetallicRoughness", {{"baseColorTexture", t}}}};
}

// The file's scene seen head-on (the quad fills the image), size x size pixels.
Scene loadQuad(const std::string& file, int size, int spp) {
  std::vector<std::string> warnings;
  Scene s = loadScene(file, warnings);
  for (const std::string& w : warnings) CHECK_MESSAGE(w.find("not used") == std::string::npos, w);
  s.camera.position = {0, 0, 2};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 1, 0};
  s.camera.fovY = float(glm::degrees(2.0 * std::atan(0.5)));
  s.camera.width = s.camera.height = size;
  s.render.spp = spp;
  return s;
}

Film render(const Scene& s, bool aovs) {
  static const DeviceInfo device = selectDevice("");
  Bvh bvh = buildBvh(s.triangles);
  RenderOptions o;
  o.aovs = aovs;
  WavefrontRenderer r(device, o);
  RenderStats stats;
  return r.render(s, bvh, stats);
}

glm::vec3 albedoAt(const Film& f, std::size_t p) { return glm::vec3(f.aovSum[MCL_AOV_VECTORS * p]) / float(f.count[p]); }

// The surface's glTF UV at the centre of pixel (px, py) of a size x size image of a quad with UVs
// uvRect(u0, u1, v0, v1).
glm::dvec2 pixelUv(int px, int py, int size, double u0, double u1, double v0, double v1) {
  return {u0 + (u1 - u0) * (px + 0.5) / size, v0 + (v1 - v0) * (py + 0.5) / size};
}

// Checks every pixel whose texture coordinate t (glTF, after transform and before wrap) is at
// least 0.2 cells from a cell edge: its albedo AOV is the linear value of the cell wrap(t) names.
// Returns the pixels checked.
int checkCells(const Film& f, int size, const std::function<glm::dvec2(int, int)>& texUv,
               const std::function<int(double)>& cellS, const std::function<int(double)>& cellT) {
  int checked = 0;
  for (int py = 0; py < size; ++py)
    for (int px = 0; px < size; ++px) {
      const glm::dvec2 t = texUv(px, py);
      const double fs = 4.0 * t.x - std::floor(4.0 * t.x), ft = 4.0 * t.y - std::floor(4.0 * t.y);
      if (fs < 0.2 || fs > 0.8 || ft < 0.2 || ft > 0.8) continue;
      const glm::vec3 got = albedoAt(f, std::size_t(py) * size + px);
      for (int c = 0; c < 3; ++c) {
        CAPTURE(px);
        CAPTURE(py);
        const float want = srgbToLinear(float(cellValue(cellS(t.x), cellT(t.y), c)) / 255.0f);
        REQUIRE(got[c] == doctest::Approx(want).epsilon(2e-3));  // half-float texels
      }
      ++checked;
    }
  return checked;
}

int repeatCell(double t) { return int(std::floor(4.0 * (t - std::floor(t)))); }

}  // namespace

TEST_CASE("KHR_texture_transform: a transformed texture's albedo is the texel the transform names, as a pre-transformed image's" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeCells(dir.file("cells.png"));
  const double ox = 0.3, oy = -0.2, rot = kPi / 6.0, sx = 2.0, sy = 1.5;
  json ext = {{"offset", {ox, oy}}, {"rotation", rot}, {"scale", {sx, sy}}};
  json g = quadGltf(uvRect(0, 1, 0, 1), {}, texturedMaterial({{"extensions", {{"KHR_texture_transform", ext}}}}));
  g["images"] = {{{"uri", "cells.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["extensionsUsed"] = {"KHR_texture_transform"};
  dir.write("t.gltf", g.dump());
  // The extension's T R S on glTF's UVs.
  const auto transform = [&](glm::dvec2 uv) {
    const double c = std::cos(rot), s = std::sin(rot);
    return glm::dvec2(c * sx * uv.x + s * sy * uv.y + ox, -s * sx * uv.x + c * sy * uv.y + oy);
  };
  const int size = 128;
  const Film f = render(loadQuad(dir.file("t.gltf"), size, 2), true);
  const auto texUv = [&](int px, int py) { return transform(pixelUv(px, py, size, 0, 1, 0, 1)); };
  CHECK(checkCells(f, size, texUv, repeatCell, repeatCell) > size * size / 4);
  // The same picture baked into an image (the transform applied to its pixel centres), untransformed.
  writeImage8(dir.file("baked.png"), 256, 256, 3, [&](int x, int y, int c) {
    const glm::dvec2 t = transform({(x + 0.5) / 256.0, (y + 0.5) / 256.0});
    return cellValue(repeatCell(t.x), repeatCell(t.y), c);
  });
  g["images"] = {{{"uri", "baked.png"}}};
  g["materials"] = {texturedMaterial()};
  dir.write("baked.gltf", g.dump());
  const Film b = render(loadQuad(dir.file("baked.gltf"), size, 2), true);
  int compared = 0;
  for (int py = 0; py < size; ++py)
    for (int px = 0; px < size; ++px) {
      const glm::dvec2 t = texUv(px, py);
      const double fs = 4.0 * t.x - std::floor(4.0 * t.x), ft = 4.0 * t.y - std::floor(4.0 * t.y);
      if (fs < 0.2 || fs > 0.8 || ft < 0.2 || ft > 0.8) continue;
      // The baked image repeats: at the quad's edges its bilinear lookup meets the opposite edge.
      if (px < 2 || py < 2 || px >= size - 2 || py >= size - 2) continue;
      const std::size_t p = std::size_t(py) * size + px;
      CAPTURE(px);
      CAPTURE(py);
      for (int c = 0; c < 3; ++c) REQUIRE(albedoAt(f, p)[c] == doctest::Approx(albedoAt(b, p)[c]).epsilon(2e-3));
      ++compared;
    }
  CHECK(compared > size * size / 4);
}

TEST_CASE("sampler wrap modes: repeat, clamp to edge and mirrored repeat per axis give the expected texel" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeCells(dir.file("cells.png"));
  const auto clampCell = [](double t) { return std::min(3, std::max(0, int(std::floor(4.0 * t)))); };
  const auto mirrorCell = [](double t) {
    double m = t - 2.0 * std::floor(0.5 * t);
    if (m >= 1.0) m = 2.0 - m;
    return std::min(3, int(std::floor(4.0 * m)));
  };
  struct Case {
    int wrapS, wrapT;
    std::function<int(double)> s, t;
  };
  const std::vector<Case> cases = {{33071, 33648, clampCell, mirrorCell},
                                   {33648, 10497, mirrorCell, repeatCell},
                                   {10497, 33071, repeatCell, clampCell}};
  const int size = 96;  // UVs -1 .. 2: 8 pixels a cell
  for (const Case& k : cases) {
    CAPTURE(k.wrapS);
    CAPTURE(k.wrapT);
    json g = quadGltf(uvRect(-1, 2, -1, 2), {}, texturedMaterial());
    g["images"] = {{{"uri", "cells.png"}}};
    g["samplers"] = {{{"wrapS", k.wrapS}, {"wrapT", k.wrapT}}};
    g["textures"] = {{{"source", 0}, {"sampler", 0}}};
    dir.write("w.gltf", g.dump());
    const Film f = render(loadQuad(dir.file("w.gltf"), size, 1), true);
    const auto texUv = [&](int px, int py) { return pixelUv(px, py, size, -1, 2, -1, 2); };
    CHECK(checkCells(f, size, texUv, k.s, k.t) >= size * size / 5);
  }
}

TEST_CASE("TEXCOORD_1: a texture whose texCoord (or KHR_texture_transform's) names set 1 reads it" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeCells(dir.file("cells.png"));
  const std::vector<float> real = uvRect(0, 1, 0, 1), flat(8, 0.0f);
  const auto file = [&](const std::string& name, const std::vector<float>& uv0, const std::vector<float>& uv1,
                        const json& info) {
    json g = quadGltf(uv0, uv1, texturedMaterial(info));
    g["images"] = {{{"uri", "cells.png"}}};
    g["textures"] = {{{"source", 0}}};
    dir.write(name, g.dump());
    return render(loadQuad(dir.file(name), 64, 1), true);
  };
  const Film want = file("set0.gltf", real, {}, json::object());
  const Film bySet = file("set1.gltf", flat, real, {{"texCoord", 1}});
  const Film byExtension = file("ext1.gltf", flat, real, {{"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}});
  const Film unused = file("unused.gltf", real, flat, json::object());  // set 1 present, not named
  CHECK(bySet.aovSum == want.aovSum);
  CHECK(byExtension.aovSum == want.aovSum);
  CHECK(unused.aovSum == want.aovSum);
  const Film wrong = file("wrong.gltf", flat, real, json::object());  // set 0 read: one texel everywhere
  CHECK(wrong.aovSum != want.aovSum);
}

TEST_CASE("KHR_materials_unlit: the base colour is the radiance seen, with zero variance" * doctest::test_suite("opencl")) {
  TempDir dir;
  writeCells(dir.file("cells.png"));
  const glm::vec3 factor(0.5f, 1.0f, 0.25f);
  json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {factor.x, factor.y, factor.z, 1.0}}}},
            {"extensions", {{"KHR_materials_unlit", json::object()}}}};
  json g = quadGltf(uvRect(0, 1, 0, 1), {}, m);
  g["extensionsUsed"] = {"KHR_materials_unlit"};
  dir.write("plain.gltf", g.dump());
  Scene s = loadQuad(dir.file("plain.gltf"), 16, 8);
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].albedo == glm::vec3(0.0f));  // it reflects nothing
  for (Integrator integrator : {Integrator::Path, Integrator::Direct}) {
    s.render.integrator = integrator;
    const Film f = render(s, false);
    for (std::size_t p = 0; p < f.pixelCount(); ++p)
      for (int c = 0; c < 3; ++c) {
        REQUIRE(f.meanOf(p, c) == double(factor[c]));
        REQUIRE(f.m2Of(p, c) == 0.0);
      }
  }
  // With a base colour texture: factor x texel (interiors of the cells).
  m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  g["materials"] = json::array({m});
  g["images"] = {{{"uri", "cells.png"}}};
  g["textures"] = {{{"source", 0}}};
  dir.write("tex.gltf", g.dump());
  const int size = 64;
  const Film f = render(loadQuad(dir.file("tex.gltf"), size, 2), false);
  int checked = 0;
  for (int py = 0; py < size; ++py)
    for (int px = 0; px < size; ++px) {
      if (px % 16 < 3 || px % 16 > 12 || py % 16 < 3 || py % 16 > 12) continue;
      const std::size_t p = std::size_t(py) * size + px;
      for (int c = 0; c < 3; ++c) {
        const double want = factor[c] * srgbToLinear(float(cellValue(px / 16, py / 16, c)) / 255.0f);
        REQUIRE(f.meanOf(p, c) == doctest::Approx(want).epsilon(2e-3));
      }
      ++checked;
    }
  CHECK(checked == 16 * 10 * 10);
}

TEST_CASE("texture transform, texCoord and wrap: bad values are one line naming the key, exit 2" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeCells(dir.file("cells.png"));
  struct Case {
    std::string name, key;
    std::function<void(json&)> edit;
  };
  const std::string ext = "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform";
  const std::vector<Case> cases = {
      {"offset", ext + ".offset",
       [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {{"offset", {"a", 0}}}; }},
      {"scale", ext + ".scale",
       [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {{"scale", "big"}}; }},
      {"rotation", ext + ".rotation",
       [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {{"rotation", {1}}}; }},
      {"texcoord", "materials[0].pbrMetallicRoughness.baseColorTexture.texCoord",
       [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1; }},
      {"wrap", "samplers[0].wrapT",
       [](json& g) {
         g["samplers"] = {{{"wrapS", 33071}, {"wrapT", 12345}}};
         g["textures"][0]["sampler"] = 0;
       }},
  };
  for (const Case& k : cases) {
    CAPTURE(k.name);
    json g = quadGltf(uvRect(0, 1, 0, 1), {}, texturedMaterial());
    g["images"] = {{{"uri", "cells.png"}}};
    g["textures"] = {{{"source", 0}}};
    k.edit(g);
    const std::string file = dir.file(k.name + ".gltf"), out = dir.file(k.name + ".png");
    dir.write(k.name + ".gltf", g.dump());
    const CliResult r = runMontecl({"render", file, "-o", out, "--spp", "1", "--width", "8", "--height", "8", "-q"});
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(k.key) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(out));
    INFO(r.err);
  }
}

TEST_CASE("COLOR_0: vertex colours multiply the base colour, interpolated over each triangle" * doctest::test_suite("opencl")) {
  TempDir dir;
  // Corners bottom-left, bottom-right, top-right, top-left.
  const std::vector<glm::vec3> corner = {{1.0f, 0.2f, 0.0f}, {0.0f, 1.0f, 0.4f}, {0.6f, 0.0f, 1.0f}, {1.0f, 1.0f, 1.0f}};
  const glm::vec3 factor(0.5f, 0.8f, 1.0f);
  json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {factor.x, factor.y, factor.z, 1.0}}}}};
  std::vector<float> rgb;
  std::vector<std::uint8_t> rgba8;
  for (const glm::vec3& c : corner)
    for (int k = 0; k < 4; ++k) {
      if (k < 3) rgb.push_back(c[k]);
      rgba8.push_back(std::uint8_t(std::lround((k < 3 ? c[k] : 0.5f) * 255.0f)));  // alpha not read
    }
  const int size = 64;
  const auto expected = [&](int px, int py) {  // the triangles (0, 1, 2) and (0, 2, 3) at the pixel centre
    const double x = -1.0 + 2.0 * (px + 0.5) / size, y = 1.0 - 2.0 * (py + 0.5) / size;
    double u, v;
    glm::dvec3 a = corner[0], b, c;
    if (y <= x) u = (x + 1.0) / 2.0 - (y + 1.0) / 2.0, v = (y + 1.0) / 2.0, b = corner[1], c = corner[2];
    else u = (x + 1.0) / 2.0, v = (y + 1.0) / 2.0 - (x + 1.0) / 2.0, b = corner[2], c = corner[3];
    return glm::dvec3(factor) * (a * (1.0 - u - v) + b * u + c * v);
  };
  for (int variant = 0; variant < 2; ++variant) {
    CAPTURE(variant);
    const json g = variant == 0 ? quadGltf(uvRect(0, 1, 0, 1), {}, m, bytesOf(rgb), 5126, "VEC3")
                                : quadGltf(uvRect(0, 1, 0, 1), {}, m, bytesOf(rgba8), 5121, "VEC4");
    dir.write("c.gltf", g.dump());
    const Film f = render(loadQuad(dir.file("c.gltf"), size, 4), true);
    for (int py = 0; py < size; ++py)
      for (int px = 0; px < size; ++px) {
        const glm::dvec3 want = expected(px, py);
        const glm::vec3 got = albedoAt(f, std::size_t(py) * size + px);
        CAPTURE(px);
        CAPTURE(py);
        // Sample positions spread over the pixel: a colour changes by at most 1/32 a pixel here.
        for (int k = 0; k < 3; ++k) REQUIRE(std::fabs(got[k] - want[k]) < 0.02 + (variant ? 0.004 : 0.0));
      }
  }
  // One colour everywhere: the base colour times it (as a material of that colour).
  std::vector<float> grey;
  for (int i = 0; i < 4; ++i) grey.insert(grey.end(), {0.25f, 0.5f, 0.75f});
  dir.write("g.gltf", quadGltf(uvRect(0, 1, 0, 1), {}, m, bytesOf(grey)).dump());
  const Film f = render(loadQuad(dir.file("g.gltf"), 16, 2), true);
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    const glm::vec3 got = albedoAt(f, p);
    CHECK(got.x == doctest::Approx(0.125).epsilon(1e-5));
    CHECK(got.y == doctest::Approx(0.4).epsilon(1e-5));
    CHECK(got.z == doctest::Approx(0.75).epsilon(1e-5));
  }
}

}  // namespace test_file_texture_sampling
