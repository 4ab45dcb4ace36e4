// test_gltf_quantized.cpp: KHR_mesh_quantization through the glTF loader: POSITION, NORMAL and
// TEXCOORD_0 stored as the integer types the extension lists (normalized or not; unsigned
// positions moved back by their node's translation, as quantizers write them) load to exactly the
// float model's triangles where the quantization is lossless; a type outside the list is one line
// naming the attribute; a required extension montecl does not read is refused by name.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_gltf_quantized {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::TempDir;
using nlohmann::json;

namespace {

// One attribute's storage: glTF component type, normalized flag, and the factor from the float
// value to the stored integer (1 for integers kept as they are, 127 / 32767 / 255 / 65535 normalized).
struct Storage {
  int type = 5126;  // FLOAT
  bool normalized = false;
  float scale = 1.0f;
  float offset = 0.0f;  // added before storing (unsigned positions), undone by the node
};

std::size_t sizeOf(int type) { return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4; }

// Appends count elements of `components` values (4-byte aligned elements, as glTF requires for
// vertex attributes); returns the bufferView's stride.
std::size_t put(std::string& bin, const std::vector<float>& values, int components, const Storage& s) {
  const std::size_t size = sizeOf(s.type), stride = (size * std::size_t(components) + 3) / 4 * 4;
  for (std::size_t e = 0; e < values.size() / std::size_t(components); ++e) {
    std::string element(stride, '\0');
    for (int c = 0; c < components; ++c) {
      const float v = (values[e * std::size_t(components) + std::size_t(c)] + s.offset) * s.scale;
      char* at = &element[std::size_t(c) * size];
      // Rounded and clamped to the type's range (so a scale of 128 stores -128 and 127).
      const auto fit = [v](long lo, long hi) { return std::min(std::max(std::lround(v), lo), hi); };
      if (s.type == 5126) std::memcpy(at, &v, 4);
      else if (s.type == 5120) { const std::int8_t x = std::int8_t(fit(-128, 127)); std::memcpy(at, &x, 1); }
      else if (s.type == 5121) { const std::uint8_t x = std::uint8_t(fit(0, 255)); std::memcpy(at, &x, 1); }
      else if (s.type == 5122) { const std::int16_t x = std::int16_t(fit(-32768, 32767)); std::memcpy(at, &x, 2); }
      else { const std::uint16_t x = std::uint16_t(fit(0, 65535)); std::memcpy(at, &x, 2); }
    }
    bin += element;
  }
  return stride;
}

// A unit quad in y = 0 (two triangles, indexed), normals +y, UVs at the corners, each attribute
// stored as given; required lists extensionsRequired.
json quad(const Storage& pos, const Storage& nor, const Storage& uv, const json& required = json::array()) {
  const std::vector<float> p = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
  const std::vector<float> n = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<float> t = {0, 0, 1, 0, 1, 1, 0, 1};
  std::string bin;
  json views = json::array(), accessors = json::array();
  const auto add = [&](const std::vector<float>& v, int components, const Storage& s) {
    const std::size_t at = bin.size();
    const std::size_t stride = put(bin, v, components, s);
    views.push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", bin.size() - at}, {"byteStride", stride}});
    json a = {{"bufferView", views.size() - 1}, {"componentType", s.type}, {"count", 4}, {"type", components == 2 ? "VEC2" : "VEC3"}};
    if (s.normalized) a["normalized"] = true;
    accessors.push_back(a);
  };
  add(p, 3, pos);
  accessors[0]["min"] = {(-1 + pos.offset) * pos.scale, pos.offset * pos.scale, (-1 + pos.offset) * pos.scale};
  accessors[0]["max"] = {(1 + pos.offset) * pos.scale, pos.offset * pos.scale, (1 + pos.offset) * pos.scale};
  add(n, 3, nor);
  add(t, 2, uv);
  const std::size_t at = bin.size();
  const std::uint16_t idx[6] = {0, 2, 1, 0, 3, 2};
  bin.append(reinterpret_cast<const char*>(idx), sizeof idx);
  views.push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", sizeof idx}});
  accessors.push_back({{"bufferView", views.size() - 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  // Integer positions stored with an offset (and scale) are placed back by the node, as quantizers
  // do; normalized ones are read back to [-1, 1] by the loader itself.
  json node = {{"mesh", 0}};
  if (!pos.normalized && (pos.offset != 0.0f || pos.scale != 1.0f)) {
    const double k = 1.0 / pos.scale;
    node["matrix"] = {k, 0, 0, 0, 0, k, 0, 0, 0, 0, k, 0, -pos.offset, -pos.offset, -pos.offset, 1};
  }
  json g = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}}, {"nodes", {node}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}}}}}}},
            {"buffers", {{{"uri", "data:application/octet-stream;base64," + montecl_test::base64(bin)}, {"byteLength", bin.size()}}}},
            {"bufferViews", views}, {"accessors", accessors}};
  json used = json::array({"KHR_mesh_quantization"});
  for (const auto& r : required) used.push_back(r);
  g["extensionsUsed"] = used;
  g["extensionsRequired"] = json::array({"KHR_mesh_quantization"});
  for (const auto& r : required) g["extensionsRequired"].push_back(r);
  return g;
}

Scene load(const TempDir& dir, const json& g, std::vector<std::string>& warnings) {
  dir.write("q.gltf", g.dump());
  Scene s;
  montecl::loadGltfInto(dir.file("q.gltf"), s, &warnings, nullptr);
  return s;
}

std::string errorOf(const TempDir& dir, const json& g) {
  std::vector<std::string> w;
  try {
    load(dir, g, w);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("glTF KHR_mesh_quantization: integer and normalized attributes load to the float model's triangles" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  std::vector<std::string> warnings;
  const Scene ref = load(dir, quad({}, {}, {}), warnings);
  CHECK(warnings.empty());  // a supported extension: nothing to say
  REQUIRE(ref.triangles.size() == 2);
  struct Variant {
    const char* name;
    Storage pos, nor, uv;
  };
  const Storage f{};
  const std::vector<Variant> variants = {
      {"POSITION BYTE", {5120, false, 1, 0}, f, f},
      {"POSITION SHORT", {5122, false, 1, 0}, f, f},
      {"POSITION UNSIGNED_BYTE + node offset", {5121, false, 1, 1}, f, f},
      {"POSITION UNSIGNED_SHORT x 100 + node matrix", {5123, false, 100, 1}, f, f},
      {"POSITION BYTE normalized", {5120, true, 127, 0}, f, f},
      {"POSITION SHORT normalized", {5122, true, 32767, 0}, f, f},
      // The most negative normalized values are -1 too (glTF clamps -128 / 127 and -32768 / 32767).
      {"POSITION BYTE normalized, -128 and 127", {5120, true, 128, 0}, f, f},
      {"POSITION SHORT normalized, -32768 and 32767", {5122, true, 32768, 0}, f, f},
      {"NORMAL BYTE normalized", f, {5120, true, 127, 0}, f},
      {"NORMAL SHORT normalized", f, {5122, true, 32767, 0}, f},
      {"TEXCOORD BYTE", f, f, {5120, false, 1, 0}},
      {"TEXCOORD SHORT normalized", f, f, {5122, true, 32767, 0}},
      {"TEXCOORD UNSIGNED_BYTE normalized", f, f, {5121, true, 255, 0}},
      {"TEXCOORD UNSIGNED_SHORT", f, f, {5123, false, 1, 0}},
  };
  for (const Variant& v : variants) {
    INFO(std::string(v.name));
    warnings.clear();
    const Scene s = load(dir, quad(v.pos, v.nor, v.uv), warnings);
    REQUIRE(s.triangles.size() == ref.triangles.size());
    for (std::size_t i = 0; i < s.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 a = s.triangles[i].v[k], b = ref.triangles[i].v[k];
        INFO(a.x << " " << a.y << " " << a.z << " vs " << b.x << " " << b.y << " " << b.z);
        CHECK(a == b);
        CHECK(s.triangles[i].n[k] == ref.triangles[i].n[k]);
        CHECK(s.triangles[i].uv[k] == ref.triangles[i].uv[k]);
      }
  }
  // Outside the extension's list: a NORMAL of plain (not normalized) bytes, named by attribute.
  CHECK(errorOf(dir, quad(f, {5120, false, 1, 0}, f)).find(dir.file("q.gltf") +
                                                           ": meshes[0].primitives[0].NORMAL: expected FLOAT or "
                                                           "(KHR_mesh_quantization) normalized signed") == 0);
}

TEST_CASE("glTF extensionsRequired: every extension montecl does not read is refused by name" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  for (const char* ext : {"EXT_meshopt_compression", "KHR_something_new"}) {
    INFO(ext);
    const std::string e = errorOf(dir, quad({}, {}, {}, {ext}));
    CHECK(e.find(dir.file("q.gltf") + ": extensionsRequired[1]: extension '" + ext +
                 "' is required by the file and not supported by montecl") == 0);
  }
  // Through the command line: one line, exit 2, nothing written.
  dir.write("meshopt.gltf", quad({}, {}, {}, {"EXT_meshopt_compression"}).dump());
  const montecl_test::CliResult r = montecl_test::runMontecl({"render", dir.file("meshopt.gltf"), "-o", dir.file("d.png"), "-q"});
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find("EXT_meshopt_compression") != std::string::npos);
}

}  // namespace test_file_gltf_quantized
