// test_mesh_entry.cpp: a scene file's per-mesh "transform" (scale, rotate, translate, or a
// row-major "matrix") and "material" overrides: geometry equal to the pre-transformed mesh,
// normals by the inverse transpose, mirrors keeping faces' sides, overrides of the file's
// materials, every bad key an InputError naming its key path; and (cli) a transformed mesh renders
// the same image as the mesh transformed in the file.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "scene/scene.h"
#include "scene/scene_digest.h"
#include "util/errors.h"

namespace test_file_mesh_entry {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::TempDir;
using nlohmann::json;

namespace {

json sceneWith(const json& mesh) {
  return json{{"camera", {{"position", {0, 1, 6}}, {"target", {0, 0.5, 0}}, {"fov_y", 40}, {"width", 32}, {"height", 24}}},
              {"meshes", json::array({mesh})},
              {"render", {{"integrator", "ao"}, {"spp", 4}}}};
}

Scene loadJson(const TempDir& dir, const json& scene, std::vector<std::string>* warnings = nullptr) {
  dir.write("scene.json", scene.dump());
  std::vector<std::string> w;
  return montecl::loadScene(dir.file("scene.json"), warnings ? *warnings : w);
}

std::string loadJsonError(const TempDir& dir, const json& scene) {
  try {
    loadJson(dir, scene);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

// A unit quad in the xy plane facing +z, with normals, UVs and a material, plus a tilted triangle.
const char* kModelObj =
    "mtllib model.mtl\nusemtl m\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.25 0.5 0.75\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\nvn 0.6 0 0.8\n"
    "f 1/1/1 2/2/1 3/3/2\nf 1/1/1 3/3/2 4/4/1\nf 1 2 5\n";

// The same model under the matrix kMatrix (x' = 2z + 0.5, y' = 2x, z' = 2y + 0.25): exactly
// representable, so the transformed vertices are bit-identical to these.
const char* kMatrix = "[0,0,2,0.5, 2,0,0,0, 0,2,0,0.25, 0,0,0,1]";
const char* kModelPretransformedObj =
    "mtllib model.mtl\nusemtl m\n"
    "v 0.5 0 0.25\nv 0.5 2 0.25\nv 0.5 2 2.25\nv 0.5 0 2.25\nv 2 0.5 1.25\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 1 0 0\nvn 0.8 0.6 0\n"
    "f 1/1/1 2/2/1 3/3/2\nf 1/1/1 3/3/2 4/4/1\nf 1 2 5\n";

void writeModel(const TempDir& dir) {
  dir.write("model.obj", kModelObj);
  dir.write("pre.obj", kModelPretransformedObj);
  dir.write("model.mtl", "newmtl m\nKd 0.7 0.6 0.5\n");
}

}  // namespace

TEST_CASE("mesh transform: a matrix gives exactly the geometry of the model transformed in the file" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeModel(dir);
  Scene a = loadJson(dir, sceneWith(json{{"file", "model.obj"}, {"transform", {{"matrix", json::parse(kMatrix)}}}}));
  Scene b = loadJson(dir, sceneWith(json{{"file", "pre.obj"}}));
  REQUIRE(a.triangles.size() == b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      CHECK(a.triangles[i].v[k] == b.triangles[i].v[k]);
      CHECK(a.triangles[i].uv[k] == b.triangles[i].uv[k]);
      CHECK(glm::length(a.triangles[i].n[k] - b.triangles[i].n[k]) < 1e-6f);
    }
  CHECK(a.boundsMin == b.boundsMin);
  CHECK(a.boundsMax == b.boundsMax);
}

TEST_CASE("mesh transform: scale, then rotate, then translate; normals by the inverse transpose" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeModel(dir);
  const json t = {{"scale", {2, 3, 1}}, {"rotate", {0, 0, 2, 90}}, {"translate", {1, 0.5, -1}}};
  Scene s = loadJson(dir, sceneWith(json{{"file", "model.obj"}, {"transform", t}}));
  Scene ref = loadJson(dir, sceneWith(json{{"file", "model.obj"}}));
  REQUIRE(s.triangles.size() == ref.triangles.size());
  // 90 degrees about +z: (x, y, z) -> (-y, x, z), after the scale.
  for (std::size_t i = 0; i < s.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = ref.triangles[i].v[k] * glm::vec3(2, 3, 1);
      const glm::vec3 expect = glm::vec3(-p.y, p.x, p.z) + glm::vec3(1, 0.5f, -1);
      CHECK(glm::length(s.triangles[i].v[k] - expect) < 1e-5f);
    }
  // The corner normal (0.6, 0, 0.8) under scale (2, 3, 1): inverse transpose -> (0.3, 0, 0.8), then rotated.
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.0f, 0.8f));
  CHECK(glm::length(s.triangles[0].n[2] - glm::vec3(-n.y, n.x, n.z)) < 1e-5f);
  CHECK(std::abs(glm::length(s.triangles[0].n[2]) - 1.0f) < 1e-6f);
  // A uniform scale alone: one number.
  Scene u = loadJson(dir, sceneWith(json{{"file", "model.obj"}, {"transform", {{"scale", 0.5}}}}));
  CHECK(u.triangles[0].v[2] == glm::vec3(0.5f, 0.5f, 0.0f));
}

TEST_CASE("mesh transform: a mirror keeps every face (and emitter) facing the mirrored way" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeModel(dir);
  for (const json& t : {json{{"scale", {-1, 1, 1}}}, json{{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1}}}}) {
    Scene s = loadJson(dir, sceneWith(json{{"file", "model.obj"}, {"transform", t}, {"emission", {1, 1, 1}}}));
    const bool flipZ = t.contains("matrix");
    for (int i = 0; i < 2; ++i) {  // the quad faced +z
      const montecl::SceneTriangle& tri = s.triangles[std::size_t(i)];
      const glm::vec3 g = glm::cross(tri.v[1] - tri.v[0], tri.v[2] - tri.v[0]);
      CHECK((flipZ ? g.z < 0 : g.z > 0));
      for (int k = 0; k < 3; ++k) CHECK(glm::dot(tri.n[k], g) > 0.0f);  // shading normals on the same side
    }
    // UVs travel with their corners: (0,0) stays at the corner (0,0,0).
    CHECK(s.triangles[0].v[0] == glm::vec3(0.0f));
    CHECK(s.triangles[0].uv[0] == glm::vec2(0.0f));
    CHECK(s.triangles[0].uv[1] == glm::vec2(1, 1));  // corner 3 moved to slot 1
  }
}

TEST_CASE("mesh material: overrides replace the file's values for that mesh only" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeModel(dir);
  dir.write("wood.png", "x");
  json scene = sceneWith(json{{"file", "model.obj"},
                              {"material", {{"type", "diffuse"}, {"albedo_texture", "wood.png"}, {"emission", {2, 2, 2}}, {"alpha_cutoff", 0.25},
                                            {"specular", {0.1, 0.2, 0.3}}, {"specular_exponent", 20}, {"two_sided_emission", true}}}});
  scene["meshes"].push_back(json{{"file", "model.obj"}, {"material", {{"albedo", {0.1, 0.2, 0.3}}}}});
  scene["meshes"].push_back(json{{"file", "model.obj"}});
  Scene s = loadJson(dir, scene);
  REQUIRE(s.triangles.size() == 9);
  const montecl::MaterialDesc& a = s.materials[s.triangles[0].material];
  CHECK(a.albedoTexture == dir.file("wood.png"));
  CHECK(a.albedo == glm::vec3(1.0f));  // a texture without an albedo: the texture as it is
  CHECK(a.emission == glm::vec3(2.0f));
  CHECK(a.twoSidedEmission);
  CHECK(a.alphaCutoff == 0.25f);
  CHECK(a.specular == glm::vec3(0.1f, 0.2f, 0.3f));
  CHECK(a.specularExponent == 20.0f);
  CHECK(a.kind == MCL_MATERIAL_diffuse);
  const montecl::MaterialDesc& b = s.materials[s.triangles[3].material];
  CHECK(b.albedo == glm::vec3(0.1f, 0.2f, 0.3f));
  CHECK(b.albedoTexture.empty());
  CHECK(b.emission == glm::vec3(0.0f));
  const montecl::MaterialDesc& c = s.materials[s.triangles[6].material];
  CHECK(c.albedo == glm::vec3(0.7f, 0.6f, 0.5f));
}

TEST_CASE("mesh transform/material: every bad value is an InputError naming its key path" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeModel(dir);
  struct Case {
    json mesh;
    std::string needle;
  } cases[] = {
      {{{"transform", {{"scale", 0}}}}, "meshes[0].transform.scale: must not be 0"},
      {{{"transform", {{"scale", {1, 0, 1}}}}}, "meshes[0].transform.scale: must not be 0"},
      {{{"transform", {{"scale", "big"}}}}, "meshes[0].transform.scale: expected an array of 3 numbers"},
      {{{"transform", {{"rotate", {0, 0, 0, 90}}}}}, "meshes[0].transform.rotate: the axis must not be the zero vector"},
      {{{"transform", {{"rotate", {0, 1, 0}}}}}, "meshes[0].transform.rotate: expected [axis x, axis y, axis z, degrees]"},
      {{{"transform", {{"rotate", {0, 1, 0, "x"}}}}}, "meshes[0].transform.rotate[3]: expected a number"},
      {{{"transform", {{"translate", {0, 1e39, 0}}}}}, "meshes[0].transform.translate[1]: number out of float range"},
      {{{"transform", {{"matrix", {1, 0, 0}}}}}, "meshes[0].transform.matrix: expected 16 numbers"},
      {{{"transform", {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}}}}}, "meshes[0].transform.matrix: the last row must be 0 0 0 1"},
      {{{"transform", {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}}}}}, "meshes[0].transform.matrix: singular"},
      {{{"transform", {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}, {"scale", 2}}}}, "meshes[0].transform.scale: give either"},
      {{{"transform", {{"scale", 1e38}, {"translate", {3e38, 0, 0}}}}}, "meshes[0].transform: moves vertices out of float range"},
      {{{"transform", 3}}, "meshes[0].transform: expected an object"},
      {{{"material", {{"albedo", {1, -1, 1}}}}}, "meshes[0].material.albedo: components must be >= 0"},
      {{{"material", {{"albedo_texture", "gone.png"}}}}, "meshes[0].material.albedo_texture: cannot open"},
      {{{"material", {{"alpha_texture", ""}}}}, "meshes[0].material.alpha_texture: empty a file name"},
      {{{"material", {{"alpha_cutoff", 2}}}}, "meshes[0].material.alpha_cutoff: must be in [0, 1]"},
      {{{"material", {{"specular", {0, 2, 0}}}}}, "meshes[0].material.specular: components must be in [0, 1]"},
      {{{"material", {{"specular_exponent", -1}}}}, "meshes[0].material.specular_exponent: must be >= 0"},
      {{{"material", {{"two_sided_emission", 1}}}}, "meshes[0].material.two_sided_emission: expected true or false"},
      {{{"material", {{"emission", {1, 1, 1}}}}, {"emission", {1, 1, 1}}}, "meshes[0].emission: also given as meshes[0].material.emission"},
      {{{"material", "red"}}, "meshes[0].material: expected an object"},
      {{{"material", {{"type", "glass"}}}}, "meshes[0].material.type: unknown material type 'glass' (known: " + std::string(materialKindNames()) + ")"},
      {{{"material", {{"type", 3}}}}, "meshes[0].material.type: expected a material type"},
  };
  for (Case& c : cases) {
    c.mesh["file"] = "model.obj";
    const std::string message = loadJsonError(dir, sceneWith(c.mesh));
    INFO(c.mesh.dump() << " -> " << message);
    CHECK(message.find("scene.json: " + c.needle) != std::string::npos);
  }
  std::vector<std::string> warnings;
  loadJson(dir, sceneWith(json{{"file", "model.obj"}, {"transform", {{"sclae", 2}}}, {"material", {{"color", 1}}}}), &warnings);
  CHECK(warnings.size() == 2);
  for (const std::string& w : warnings) CHECK((w.find("meshes[0].transform.sclae: unknown key") != std::string::npos ||
                                               w.find("meshes[0].material.color: unknown key") != std::string::npos));
}

TEST_CASE("cli: a mesh transformed by the scene file renders the image of the mesh transformed in the file" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeModel(dir);
  dir.write("a.json", sceneWith(json{{"file", "model.obj"}, {"transform", {{"matrix", json::parse(kMatrix)}}}}).dump());
  dir.write("b.json", sceneWith(json{{"file", "pre.obj"}}).dump());
  for (const char* s : {"a", "b"}) {
    auto r = montecl_test::runMontecl({"render", dir.file(std::string(s) + ".json"), "-o", dir.file(std::string(s) + ".exr"), "-q"});
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
  }
  const montecl::LayeredImage a = montecl::readLayeredImage(dir.file("a.exr"));
  const montecl::LayeredImage b = montecl::readLayeredImage(dir.file("b.exr"));
  REQUIRE(a.channels == b.channels);
  double sum = 0.0;
  for (std::size_t c = 0; c < a.planes.size(); ++c) {
    CHECK(a.planes[c] == b.planes[c]);
    for (float v : a.planes[c]) sum += v;
  }
  CHECK(sum > 0.0);  // the model is in view
}

}  // namespace test_file_mesh_entry
