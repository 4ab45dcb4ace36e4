// test_gltf.cpp: the glTF 2.0 loader (host/scene/gltf_mesh.cpp, gltf_model.cpp): .gltf with an
// external or a data-URI buffer and .glb give exactly the OBJ's triangles (v flipped back to OBJ's
// convention); node hierarchies with TRS and matrices; materials (base colour x texture, MASK cut-outs and
// BLEND transparency, emission x KHR_materials_emissive_strength, embedded images held in memory); the first
// perspective camera; triangle strips and fans as their TRIANGLES lists; one warning per unused kind;
// malformed files as one InputError line.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_gltf {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::countContaining;
using montecl_test::TempDir;
using nlohmann::json;

namespace {

Scene loadGltf(const std::string& path, std::vector<std::string>* warnings = nullptr, montecl::Camera* cam = nullptr,
               bool* hasCamera = nullptr) {
  Scene s;
  std::vector<std::string> w;
  const bool has = montecl::loadGltfInto(path, s, warnings ? warnings : &w, cam);
  if (hasCamera) *hasCamera = has;
  return s;
}

std::string gltfError(const std::string& path) {
  try {
    loadGltf(path);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

// The tent as .gltf JSON with its buffer embedded, for tests to edit.
json tentGltf() { return json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, "")); }

std::string allLines(const std::vector<std::string>& lines) {
  std::string all;
  for (const auto& l : lines) all += l + "\n";
  return all;
}

}  // namespace

TEST_CASE("glTF: external buffer, data-URI buffer and GLB give exactly the OBJ's triangles" * doctest::test_suite("cpu")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  dir.write("tent.obj", montecl_test::objText(tent));
  Scene obj;
  montecl::loadObjInto(dir.file("tent.obj"), obj);
  dir.write("ext.gltf", montecl_test::gltfText(tent, 0.5f, "ext.bin"));
  dir.write("ext.bin", montecl_test::gltfBuffer(tent));
  dir.write("embedded.gltf", montecl_test::gltfText(tent, 0.5f, ""));
  dir.write("tent.glb", montecl_test::glbBytes(tent, 0.5f));
  for (const char* name : {"ext.gltf", "embedded.gltf", "tent.glb"}) {
    INFO(name);
    std::vector<std::string> warnings;
    Scene g = loadGltf(dir.file(name), &warnings);
    CHECK(warnings.empty());
    REQUIRE(g.triangles.size() == obj.triangles.size());
    for (std::size_t i = 0; i < g.triangles.size(); ++i) {
      const montecl::SceneTriangle &a = obj.triangles[i], &b = g.triangles[i];
      CHECK(a.attributes == b.attributes);
      for (int k = 0; k < 3; ++k) {
        CHECK(a.v[k] == b.v[k]);
        CHECK(a.n[k] == b.n[k]);
        CHECK(a.uv[k] == b.uv[k]);
      }
      CHECK(g.materials[b.material].albedo == obj.materials[a.material].albedo);
    }
  }
  Scene ext = loadGltf(dir.file("ext.gltf"));
  CHECK(ext.inputFiles == std::vector<std::string>{dir.file("ext.gltf"), dir.file("ext.bin")});
}

TEST_CASE("glTF: node hierarchy with TRS and matrices; mirrors keep faces' sides; non-indexed primitives" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  json g = tentGltf();
  // Node 0 (translation) -> node 1 (rotation 90 degrees about +y, scale 2) -> node 2 (matrix: x mirror) with the mesh.
  const double h = std::sqrt(0.5);
  g["nodes"] = json::array({json{{"translation", {1, 2, 3}}, {"children", {1}}},
                            json{{"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}, {"children", {2}}},
                            json{{"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}, {"mesh", 0}}});
  dir.write("tree.gltf", g.dump());
  Scene s = loadGltf(dir.file("tree.gltf"));
  dir.write("tent.obj", montecl_test::objText(montecl_test::tentMesh()));
  Scene ref;
  montecl::loadObjInto(dir.file("tent.obj"), ref);
  REQUIRE(s.triangles.size() == ref.triangles.size());
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    // p -> mirror x -> scale 2 -> rotate +90 about y ((x, y, z) -> (z, y, -x)) -> translate.
    const glm::vec3 a = ref.triangles[i].v[0];
    const glm::vec3 m(-a.x * 2, a.y * 2, a.z * 2);
    CHECK(glm::length(s.triangles[i].v[0] - (glm::vec3(m.z, m.y, -m.x) + glm::vec3(1, 2, 3))) < 1e-5f);
    // The mirrored triangle still has its shading normals on its front side.
    const montecl::SceneTriangle& t = s.triangles[i];
    const glm::vec3 gn = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    for (int k = 0; k < 3; ++k) CHECK(glm::dot(gn, t.n[k]) > 0.0f);
  }
  // Non-indexed: the same primitive without "indices" reads vertices in order (6 -> 2 triangles).
  json ni = tentGltf();
  ni["meshes"][0]["primitives"][0].erase("indices");
  dir.write("ni.gltf", ni.dump());
  CHECK(loadGltf(dir.file("ni.gltf")).triangles.size() == 2);
  // Other modes: skipped with one warning per mode.
  json lines = tentGltf();
  auto prim = lines["meshes"][0]["primitives"][0];
  lines["meshes"][0]["primitives"] = json::array({prim, prim, prim});
  lines["meshes"][0]["primitives"][1]["mode"] = 1;
  lines["meshes"][0]["primitives"][2]["mode"] = 1;
  dir.write("lines.gltf", lines.dump());
  std::vector<std::string> warnings;
  CHECK(loadGltf(dir.file("lines.gltf"), &warnings).triangles.size() == 4);
  INFO(allLines(warnings));
  CHECK(warnings.size() == 1);
  CHECK(countContaining(warnings, "meshes[0].primitives[1]: primitive mode 1 (points or lines, not triangles) skipped (1 more like it; -v lists them)") == 1);
}

TEST_CASE("glTF: base colour x texture, MASK cut-outs, BLEND transparency, emission x strength, embedded images kept in memory" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("wood 1.png", "x");
  json g = tentGltf();
  g["images"] = json::array({json{{"uri", "wood%201.png"}}, json{{"uri", "data:image/png;base64,iVBORw0KGgo="}}});
  g["textures"] = json::array({json{{"source", 0}}, json{{"source", 1}}});
  g["materials"] = json::array(
      {json{{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}}, {"baseColorTexture", {{"index", 0}}}}},
            {"alphaMode", "MASK"}, {"alphaCutoff", 0.3}},
       json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}, {"alphaMode", "BLEND"},
            {"emissiveFactor", {1, 0.5, 0}}, {"doubleSided", true},
            {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}}});
  g["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_texture_transform", "KHR_materials_iridescence"};
  auto prim = g["meshes"][0]["primitives"][0];
  g["meshes"][0]["primitives"] = json::array({prim, prim});
  g["meshes"][0]["primitives"][1]["material"] = 1;
  dir.write("m.gltf", g.dump());
  std::vector<std::string> warnings;
  Scene s = loadGltf(dir.file("m.gltf"), &warnings);
  REQUIRE(s.triangles.size() == 8);
  const montecl::MaterialDesc& a = s.materials[s.triangles[0].material];
  CHECK(a.albedo == glm::vec3(0.5f, 0.25f, 1.0f));
  CHECK(a.albedoTexture == dir.file("wood 1.png"));
  CHECK(a.alphaTexture == a.albedoTexture);
  CHECK(a.alphaCutoff == 0.3f);
  const montecl::MaterialDesc& b = s.materials[s.triangles[4].material];
  CHECK(b.emission == glm::vec3(4.0f, 2.0f, 0.0f));
  CHECK(b.twoSidedEmission);
  // Embedded: named after the glTF and the image, its bytes (the data URI's, decoded) kept.
  CHECK(b.albedoTexture == dir.file("m.gltf") + "#images[1].png");
  REQUIRE(s.embeddedImages.count(b.albedoTexture) == 1);
  CHECK(s.embeddedImages.at(b.albedoTexture).size() == 8);
  CHECK(b.alphaTexture == b.albedoTexture);
  CHECK(b.alphaBlend);  // stochastic transparency: factor 1 x the texture's alpha
  CHECK(b.alphaFactor == 1.0f);
  CHECK(!a.alphaBlend);
  INFO(allLines(warnings));
  CHECK(countContaining(warnings, "embedded image") == 0);
  CHECK(countContaining(warnings, "BLEND") == 0);
  CHECK(countContaining(warnings, "m.gltf: extensionsUsed: extension 'KHR_materials_iridescence' not used by montecl") == 1);
  CHECK(countContaining(warnings, "KHR_texture_transform") == 0);  // read (test_texture_sampling.cpp)
  CHECK(countContaining(warnings, "emissive_strength' not used") == 0);
  // A texture file that is not there: an error naming the image.
  g["images"][0]["uri"] = "gone.png";
  dir.write("m.gltf", g.dump());
  CHECK(gltfError(dir.file("m.gltf")).find(dir.file("m.gltf") + ": images[0]: cannot open '" + dir.file("gone.png") + "'") == 0);
}

TEST_CASE("glTF: the first perspective camera becomes the camera (position, target, up, fov, aspect)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  json g = tentGltf();
  const double h = std::sqrt(0.5);
  g["cameras"] = json::array({json{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"zfar", 10}, {"znear", 0.1}}}},
                              json{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"aspectRatio", 1.5}, {"znear", 0.1}}}}});
  // A camera node at (0, 1, 5) turned 90 degrees about +y: it looks along -x.
  g["nodes"].push_back(json{{"camera", 0}});
  g["nodes"].push_back(json{{"camera", 1}, {"translation", {0, 1, 5}}, {"rotation", {0, h, 0, h}}});
  g["scenes"][0]["nodes"] = {0, 1, 2};
  dir.write("cam.gltf", g.dump());
  std::vector<std::string> warnings;
  montecl::Camera cam;
  bool has = false;
  loadGltf(dir.file("cam.gltf"), &warnings, &cam, &has);
  REQUIRE(has);
  CHECK(glm::length(cam.position - glm::vec3(0, 1, 5)) < 1e-6f);
  CHECK(glm::length(glm::normalize(cam.target - cam.position) - glm::vec3(-1, 0, 0)) < 1e-6f);
  CHECK(glm::length(cam.up - glm::vec3(0, 1, 0)) < 1e-6f);
  CHECK(cam.fovY == doctest::Approx(0.5 * 180.0 / M_PI));
  CHECK(cam.width == 768);
  CHECK(cam.height == 512);
  CHECK(countContaining(warnings, "camera type 'orthographic' not used") == 1);
  // No camera in the file: none returned.
  dir.write("nocam.gltf", tentGltf().dump());
  loadGltf(dir.file("nocam.gltf"), nullptr, &cam, &has);
  CHECK(!has);
}

TEST_CASE("glTF: malformed files are one InputError line naming the file and where" * doctest::test_suite("cpu")) {
  TempDir dir;
  auto edit = [](auto f) {
    json g = tentGltf();
    f(g);
    return g.dump();
  };
  struct Case {
    std::string name, text, needle;
  } cases[] = {
      {"a.gltf", "{\"asset\": ", "line 1, column 11: not valid glTF JSON: syntax error"},
      {"a.gltf", "ply\nformat ascii 1.0\n", "line 1, column 1: not valid glTF JSON"},
      {"a.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": 3}", "no triangles"},
      {"a.glb", "{}", "not a binary glTF"},
      {"a.glb", std::string("glTF\2\0\0\0\x40\0\0\0", 12), "not a valid GLB: "},
      {"a.gltf", edit([](json& g) { g["buffers"][0]["uri"] = "gone.bin"; }), "buffers: cannot open '"},
      {"a.gltf", edit([](json& g) { g["accessors"][0]["count"] = 1000; }), "meshes[0].primitives[0].POSITION: accessor runs past the end of its bufferView"},
      {"a.gltf", edit([](json& g) { g["accessors"][0]["type"] = "VEC2"; }), "meshes[0].primitives[0].POSITION: expected a VEC3 accessor"},
      {"a.gltf", edit([](json& g) { g["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 40; }), "meshes[0].primitives[0].POSITION: accessor index 40 out of range"},
      {"a.gltf", edit([](json& g) { g["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }), "meshes[0].primitives[0]: primitive without POSITION"},
      {"a.gltf", edit([](json& g) { g["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 1; }), "meshes[0].primitives[0].TANGENT: expected a VEC4 accessor"},
      {"a.gltf", edit([](json& g) { g["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 40; }), "meshes[0].primitives[0].TANGENT: accessor index 40 out of range"},
      {"a.gltf", edit([](json& g) { g["accessors"][3]["count"] = 4; }), "meshes[0].primitives[0]: 4 vertices do not make whole triangles"},
      {"a.gltf", edit([](json& g) { g["accessors"][3]["componentType"] = 5126; }), "meshes[0].primitives[0].indices: indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"},
      {"a.gltf", edit([](json& g) { g["bufferViews"][0]["byteLength"] = 100000; }), "meshes[0].primitives[0].POSITION: bufferView 0 runs past the end of its buffer"},
      {"a.gltf", edit([](json& g) { g["nodes"][0]["children"] = {0}; }), "nodes[0]: node reached twice"},
      {"a.gltf", edit([](json& g) { g["nodes"][0]["mesh"] = 7; }), "nodes[0]: mesh index out of range"},
      {"a.gltf", edit([](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {-1, 0, 0, 1}; }), "materials[0]: baseColorFactor must be finite and >= 0"},
      {"a.gltf", edit([](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 3}}; }), "materials[0]: baseColorTexture index out of range"},
      {"a.gltf", edit([](json& g) { g["scenes"][0]["nodes"] = json::array(); }), "no triangles"},
      // Only points (mode 0): the message says why nothing is left (the skip warning is not shown).
      {"a.gltf", edit([](json& g) { g["meshes"][0]["primitives"][0]["mode"] = 0; }), "no triangles (1 point or line primitives skipped, 0 degenerate"},
  };
  for (const Case& c : cases) {
    dir.write(c.name, c.text);
    const std::string message = gltfError(dir.file(c.name));
    INFO(c.text.substr(0, 200) << "\n -> " << message);
    CHECK(message.find(dir.file(c.name) + ": " + c.needle) == 0);
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.find("malformed JSON") == std::string::npos);
  }
}

TEST_CASE("glTF: a scene file without a camera takes the glTF mesh's, moved by the mesh's transform" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  json g = tentGltf();
  g["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
  g["nodes"].push_back({{"camera", 0}, {"translation", {0, 1, 5}}});
  g["scenes"][0]["nodes"] = {0, 1};
  dir.write("cam.gltf", g.dump());
  dir.write("tent.obj", montecl_test::objText(montecl_test::tentMesh()));
  dir.write("scene.json", json{{"meshes", {{{"file", "tent.obj"}}, {{"file", "cam.gltf"}, {"transform", {{"translate", {10, 0, 0}}}}}}}}.dump());
  std::vector<std::string> warnings;
  Scene s = montecl::loadScene(dir.file("scene.json"), warnings);
  CHECK(s.camera.position == glm::vec3(10, 1, 5));
  CHECK(s.camera.target == glm::vec3(10, 1, 4));
  CHECK(s.camera.width == 512);
  // Neither the scene file nor a glTF gives a camera: the key is missing.
  dir.write("nocam.json", json{{"meshes", {{{"file", "tent.obj"}}}}}.dump());
  try {
    montecl::loadScene(dir.file("nocam.json"), warnings);
    FAIL("loaded without a camera");
  } catch (const montecl::InputError& e) {
    CHECK(std::string(e.what()).find(dir.file("nocam.json") + ": camera: missing required key (and no glTF mesh has a camera)") == 0);
  }
}

TEST_CASE("glTF: a triangle strip and a fan give the triangles of the equivalent TRIANGLES list, winding kept" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  // The strip zigzags along x; the fan is a hexagon: centre, then six ring points and the first again.
  std::vector<float> strip, fan;
  for (int i = 0; i < 8; ++i) strip.insert(strip.end(), {float(i / 2), float(i % 2), 0.0f});
  fan.insert(fan.end(), {0.0f, 0.0f, 0.0f});
  const float ring[7][2] = {{1, 0}, {0.5f, 0.75f}, {-0.5f, 0.75f}, {-1, 0}, {-0.5f, -0.75f}, {0.5f, -0.75f}, {1, 0}};
  for (const auto& r : ring) fan.insert(fan.end(), {r[0], r[1], 0.0f});
  // The same triangles written out as lists, in the order the glTF specification gives: strip
  // triangle i is (i, i+1+i%2, i+2-i%2), fan triangle i is (i+1, i+2, 0).
  const std::vector<std::uint32_t> stripList = {0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4, 4, 5, 6, 5, 7, 6};
  const std::vector<std::uint32_t> fanList = {1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 6, 0, 6, 7, 0};
  std::string bin;
  const auto put = [&bin](const void* p, std::size_t n) { bin.append(static_cast<const char*>(p), n); };
  put(strip.data(), 96);
  put(fan.data(), 96);
  put(stripList.data(), 72);
  put(fanList.data(), 72);
  json base = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}}, {"nodes", {{{"mesh", 0}}}},
               {"buffers", {{{"uri", "data:application/octet-stream;base64," + montecl_test::base64(bin)}, {"byteLength", bin.size()}}}},
               {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 96}},
                                {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 96}},
                                {{"buffer", 0}, {"byteOffset", 192}, {"byteLength", 72}},
                                {{"buffer", 0}, {"byteOffset", 264}, {"byteLength", 72}}}}};
  for (int v = 0; v < 2; ++v)
    base["accessors"].push_back({{"bufferView", v}, {"componentType", 5126}, {"count", 8}, {"type", "VEC3"},
                                 {"min", {-1, -0.75, 0}}, {"max", {3, 1, 0}}});
  for (int v = 2; v < 4; ++v) base["accessors"].push_back({{"bufferView", v}, {"componentType", 5125}, {"count", 18}, {"type", "SCALAR"}});
  const auto load = [&](const std::string& name, json primitive) {
    json g = base;
    g["meshes"] = {{{"primitives", {primitive}}}};
    dir.write(name, g.dump());
    std::vector<std::string> warnings;
    Scene s = loadGltf(dir.file(name), &warnings);
    INFO(name << ": " << allLines(warnings));
    CHECK(warnings.empty());
    return s;
  };
  for (int shape = 0; shape < 2; ++shape) {
    const int mode = shape == 0 ? 5 : 6;
    INFO("mode " << mode);
    const Scene list = load("list.gltf", {{"attributes", {{"POSITION", shape}}}, {"indices", 2 + shape}});
    const Scene direct = load("direct.gltf", {{"attributes", {{"POSITION", shape}}}, {"mode", mode}});
    REQUIRE(list.triangles.size() == 6);
    REQUIRE(direct.triangles.size() == 6);
    for (std::size_t i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k) CHECK(direct.triangles[i].v[k] == list.triangles[i].v[k]);
    // Every triangle faces the way the first does (a strip's every other triangle is flipped back).
    for (const montecl::SceneTriangle& t : direct.triangles) {
      const montecl::SceneTriangle& f = direct.triangles[0];
      CHECK(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]).z * glm::cross(f.v[1] - f.v[0], f.v[2] - f.v[0]).z > 0.0f);
    }
  }
  // Fewer than three vertices make no triangle (and no error); points and lines stay skipped.
  base["accessors"][0]["count"] = 2;
  json g = base;
  g["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", 5}}, {{"attributes", {{"POSITION", 1}}}, {"mode", 6}}}}}};
  dir.write("short.gltf", g.dump());
  CHECK(loadGltf(dir.file("short.gltf")).triangles.size() == 6);
}

}  // namespace test_file_gltf
