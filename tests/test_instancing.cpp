// test_instancing.cpp: instanced meshes: glTF EXT_mesh_gpu_instancing (TRANSLATION / ROTATION /
// SCALE per instance, after the node's world matrix) gives exactly the triangles and the image of
// one explicit child node per instance; a scene file's "instances" list, flattened, gives exactly
// the triangles of one mesh entry per transform; bad instance accessors and lists are one line
// naming the key (exit 2), and copies past the memory check are refused up front (emitting
// instances stay copies; others are one mesh, test_instances_render.cpp).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "scene/scene_instances.h"

namespace test_file_instancing {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
using nlohmann::json;

namespace {

std::string floatBytes(const std::vector<float>& v) {
  std::string b(v.size() * 4, '\0');
  std::memcpy(&b[0], v.data(), b.size());
  return b;
}

// Appends a buffer (data URI) with one view and one FLOAT accessor of `type` over `values`;
// returns the accessor's index.
int addAccessor(json& g, const std::vector<float>& values, const char* type, std::size_t count) {
  const std::string bytes = floatBytes(values);
  g["buffers"].push_back({{"uri", "data:application/octet-stream;base64," + montecl_test::base64(bytes)},
                          {"byteLength", bytes.size()}});
  g["bufferViews"].push_back({{"buffer", g["buffers"].size() - 1}, {"byteOffset", 0}, {"byteLength", bytes.size()}});
  g["accessors"].push_back({{"bufferView", g["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", count}, {"type", type}});
  return int(g["accessors"].size() - 1);
}

struct Instances {
  std::vector<float> t, r, s;
};

// n instances with translations, unit quaternions (normalised in float) and scales that differ per instance.
Instances someInstances(int n) {
  Instances in;
  for (int i = 0; i < n; ++i) {
    in.t.insert(in.t.end(), {0.7f * float(i), 0.3f * float(i % 3), -1.1f * float(i)});
    float q[4] = {0.1f + 0.2f * float(i), -0.3f, 0.05f * float(i), 0.9f};
    const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (float& c : q) c /= len;
    in.r.insert(in.r.end(), q, q + 4);
    in.s.insert(in.s.end(), {1.0f + 0.1f * float(i), 0.8f, i % 2 ? -1.0f : 1.0f});  // some mirror
  }
  return in;
}

json tent() { return json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, "")); }

// The tent's node 0 with a parent transform and the instances through the extension.
json instancedGltf(const Instances& in, std::size_t n) {
  json g = tent();
  g["nodes"][0] = {{"mesh", 0}, {"translation", {0.5, -0.25, 0.125}}, {"scale", {2, 2, 2}}};
  json attrs = {{"TRANSLATION", addAccessor(g, in.t, "VEC3", n)},
                {"ROTATION", addAccessor(g, in.r, "VEC4", n)},
                {"SCALE", addAccessor(g, in.s, "VEC3", n)}};
  g["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = attrs;
  g["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  g["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
  return g;
}

// The same as one child node per instance (the floats as doubles: exact).
json explicitGltf(const Instances& in, std::size_t n) {
  json g = tent();
  g["nodes"][0] = {{"translation", {0.5, -0.25, 0.125}}, {"scale", {2, 2, 2}}, {"children", json::array()}};
  for (std::size_t k = 0; k < n; ++k) {
    const auto d = [](float f) { return double(f); };
    g["nodes"].push_back({{"mesh", 0},
                          {"translation", {d(in.t[3 * k]), d(in.t[3 * k + 1]), d(in.t[3 * k + 2])}},
                          {"rotation", {d(in.r[4 * k]), d(in.r[4 * k + 1]), d(in.r[4 * k + 2]), d(in.r[4 * k + 3])}},
                          {"scale", {d(in.s[3 * k]), d(in.s[3 * k + 1]), d(in.s[3 * k + 2])}}});
    g["nodes"][0]["children"].push_back(k + 1);
  }
  return g;
}

Scene loadGltf(const std::string& path) {
  Scene s;
  std::vector<std::string> w;
  montecl::loadGltfInto(path, s, &w, nullptr);
  return s;
}

void checkSameTriangles(const Scene& a, const Scene& b) {
  REQUIRE(a.triangles.size() == b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    const montecl::SceneTriangle &x = a.triangles[i], &y = b.triangles[i];
    CAPTURE(i);
    CHECK(x.attributes == y.attributes);
    for (int k = 0; k < 3; ++k) {
      CHECK(x.v[k] == y.v[k]);  // exact
      CHECK(x.n[k] == y.n[k]);
      CHECK(x.uv[k] == y.uv[k]);
    }
  }
}

CliResult render(const std::string& scene, const std::string& out, const std::vector<std::string>& env = {}) {
  return renderOnHost(scene, out, {"--spp", "2", "--integrator", "path"}, env, 16, 12);
}

}  // namespace

TEST_CASE("instancing: EXT_mesh_gpu_instancing gives the triangles and image of one child node per instance" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::size_t n = 5;
  const Instances in = someInstances(int(n));
  dir.write("inst.gltf", instancedGltf(in, n).dump());
  dir.write("nodes.gltf", explicitGltf(in, n).dump());
  const Scene a = loadGltf(dir.file("inst.gltf")), b = loadGltf(dir.file("nodes.gltf"));
  CHECK(a.triangles.size() == 4);  // the tent once, placed n times (Scene::instances)
  checkSameTriangles(a, b);
  REQUIRE(a.instances.size() == n);
  REQUIRE(b.instances.size() == n);
  for (std::size_t k = 0; k < n; ++k) CHECK(a.instances[k].objectToWorld == b.instances[k].objectToWorld);  // exact
  Scene flatA = a, flatB = b;
  montecl::flattenInstances(flatA);
  montecl::flattenInstances(flatB);
  CHECK(flatA.triangles.size() == 4 * n);  // 4 triangles per tent
  checkSameTriangles(flatA, flatB);
  // Through the real command line, with the camera and sky of a bare model: the same bytes.
  const CliResult ra = render(dir.file("inst.gltf"), dir.file("inst.pfm"));
  const CliResult rb = render(dir.file("nodes.gltf"), dir.file("nodes.pfm"));
  REQUIRE_MESSAGE(ra.exitCode == 0, ra.err);
  REQUIRE_MESSAGE(rb.exitCode == 0, rb.err);
  CHECK(ra.err.find("EXT_mesh_gpu_instancing") == std::string::npos);  // read, not warned about
  CHECK(montecl_test::readAll(dir.file("inst.pfm")) == montecl_test::readAll(dir.file("nodes.pfm")));
}

TEST_CASE("instancing: a glTF's shared mesh under a scene-file entry: the transform composes, emission or instances copy" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  const std::size_t n = 4;
  const Instances in = someInstances(int(n));
  dir.write("nodes.gltf", explicitGltf(in, n).dump());
  const json transform = {{"rotate", {1, 0.5, 0, 30}}, {"scale", {1.5, 0.5, -1}}, {"translate", {-1, 0.25, 0}}};
  const json camera = {{"position", {1, 3, 6}}, {"target", {0, 0, -1}}, {"width", 16}, {"height", 12}};
  const auto load = [&](const json& entry) {
    dir.write("scene.json", json{{"camera", camera}, {"meshes", {entry}}}.dump());
    std::vector<std::string> w;
    return montecl::loadScene(dir.file("scene.json"), w);
  };
  // Composed: the flattened placements equal the file's copies transformed vertex by vertex (in
  // double: translate x rotate x scale; the scale mirrors, so corners 1 and 2 swap).
  Scene bare = loadGltf(dir.file("nodes.gltf"));
  montecl::flattenInstances(bare);
  const Scene plain = load({{"file", "nodes.gltf"}, {"transform", transform}, {"material", {{"albedo", {0.2, 0.4, 0.6}}}}});
  CHECK(plain.triangles.size() == 4);
  REQUIRE(plain.instances.size() == n);
  CHECK(plain.materials[plain.triangles[0].material].albedo == glm::vec3(0.2f, 0.4f, 0.6f));
  Scene flat = plain;
  montecl::flattenInstances(flat);
  REQUIRE(flat.triangles.size() == bare.triangles.size());
  glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(-1, 0.25, 0));
  t = glm::rotate(t, glm::radians(30.0), glm::normalize(glm::dvec3(1, 0.5, 0)));
  t = glm::scale(t, glm::dvec3(1.5, 0.5, -1));
  for (std::size_t i = 0; i < flat.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = flat.triangles[i].v[k];
      const glm::vec3 b(t * glm::dvec4(glm::dvec3(bare.triangles[i].v[k == 0 ? 0 : 3 - k]), 1.0));
      CHECK(glm::length(a - b) <= 1e-5f * (1.0f + glm::length(b)));
    }
  // An override that makes them emit: copies (the emitter table is world space).
  const Scene copied = load({{"file", "nodes.gltf"}, {"transform", transform}, {"emission", {1, 1, 1}}});
  CHECK(copied.instances.empty());
  CHECK(copied.triangles.size() == bare.triangles.size());
  // The entry's own instances: copies of the file's placements, then the entry's mesh placed.
  const Scene twice = load({{"file", "nodes.gltf"}, {"instances", {{{"translate", {0, 0, 0}}}, {{"translate", {3, 0, 0}}}}}});
  CHECK(twice.meshRanges.size() == 1);
  CHECK(twice.triangles.size() == 4 * n);
  CHECK(twice.instances.size() == 2);
}

TEST_CASE("instancing: bad EXT_mesh_gpu_instancing accessors are one line naming the attribute, exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const Instances in = someInstances(3);
  const std::string key = ": nodes[0].extensions.EXT_mesh_gpu_instancing.attributes.";
  struct Case {
    std::string what, needle;
    json g;
  } cases[] = {{"wrong type", key + "ROTATION: expected a VEC4", instancedGltf(in, 3)},
               {"count mismatch", key + "SCALE: has 2 elements", instancedGltf(in, 3)},
               {"not finite", key + "TRANSLATION: element 1 is not finite", instancedGltf(in, 3)},
               {"zero quaternion", key + "ROTATION: element 2 is a zero quaternion", instancedGltf(in, 3)},
               {"index", key + "TRANSLATION: accessor index 99 out of range", instancedGltf(in, 3)}};
  const auto attrs = [](json& g) -> json& { return g["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]; };
  {
    json& g = cases[0].g;
    g["accessors"][int(attrs(g)["ROTATION"])]["type"] = "VEC3";
  }
  {
    json& g = cases[1].g;
    Instances two = in;
    two.s.resize(6);
    attrs(g)["SCALE"] = addAccessor(g, two.s, "VEC3", 2);
  }
  {
    json& g = cases[2].g;
    Instances nan = in;
    nan.t[4] = std::numeric_limits<float>::quiet_NaN();
    attrs(g)["TRANSLATION"] = addAccessor(g, nan.t, "VEC3", 3);
  }
  {
    json& g = cases[3].g;
    Instances zero = in;
    for (int c = 0; c < 4; ++c) zero.r[8 + c] = 0.0f;
    attrs(g)["ROTATION"] = addAccessor(g, zero.r, "VEC4", 3);
  }
  attrs(cases[4].g)["TRANSLATION"] = 99;
  for (Case& c : cases) {
    CAPTURE(c.what);
    dir.write("bad.gltf", c.g.dump());
    const CliResult r = render(dir.file("bad.gltf"), dir.file("out.pfm"));
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(dir.file("bad.gltf") + c.needle) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("out.pfm")));
  }
}

TEST_CASE("instancing: instance counts past the memory check are refused before the copies are made" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  // 10 and 10000 instances of the 4-triangle tent on a machine declared to have 2 MB: 40000
  // triangles need megabytes (the 16x12 image fits).
  for (std::size_t n : {std::size_t(10), std::size_t(10000)}) {
    CAPTURE(n);
    const Instances in = someInstances(int(n));
    json emitting = instancedGltf(in, n);  // emitting instances are copies (the emitter table is world space)
    emitting["materials"][0]["emissiveFactor"] = {1, 1, 1};
    dir.write("many.gltf", emitting.dump());
    const CliResult r = render(dir.file("many.gltf"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=2000000"});
    INFO(r.err);
    if (n == 10) {
      CHECK(r.exitCode == 0);
      std::filesystem::remove(dir.file("out.pfm"));
    } else {
      CHECK(r.exitCode == 2);
      CHECK(oneLine(r.err));
      CHECK(r.err.find(dir.file("many.gltf") + ": nodes[0]: instancing its meshes gives 40000 triangles") != std::string::npos);
      CHECK_FALSE(std::filesystem::exists(dir.file("out.pfm")));
      // Not emitting: one mesh placed 10000 times, about 4.8 MB of placements: refused at 2 MB,
      // naming the instances; it fits in 8 MB (the 40000 copied triangles would not).
      dir.write("many.gltf", instancedGltf(in, n).dump());
      const CliResult small = render(dir.file("many.gltf"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=2000000"});
      CHECK(small.exitCode == 2);
      CHECK(oneLine(small.err));
      CHECK(small.err.find(dir.file("many.gltf") + ": nodes[0]: instancing its meshes gives 10000 instances") != std::string::npos);
      const CliResult kept = render(dir.file("many.gltf"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=8000000"});
      CHECK_MESSAGE(kept.exitCode == 0, kept.err);
      std::filesystem::remove(dir.file("out.pfm"));
      dir.write("many.gltf", emitting.dump());
      CHECK(render(dir.file("many.gltf"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=8000000"}).exitCode == 2);
    }
    // The scene file's instances of an emitting mesh are copies: the same rule, naming the list.
    json scene = {{"camera", "auto"}, {"meshes", {{{"file", "tent.obj"}, {"emission", {1, 1, 1}}, {"instances", json::array()}}}}};
    for (std::size_t k = 0; k < n; ++k) scene["meshes"][0]["instances"].push_back({{"translate", {0, 0, -0.01 * double(k)}}});
    dir.write("tent.obj", montecl_test::objText(montecl_test::tentMesh()));
    dir.write("scene.json", scene.dump());
    const CliResult s = render(dir.file("scene.json"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=2000000"});
    INFO(s.err);
    if (n == 10) {
      CHECK(s.exitCode == 0);
      std::filesystem::remove(dir.file("out.pfm"));
    } else {
      CHECK(s.exitCode == 2);
      CHECK(oneLine(s.err));
      CHECK(s.err.find(dir.file("scene.json") + ": meshes[0].instances: 10000 copies of the mesh gives 40000 triangles") !=
            std::string::npos);
      CHECK_FALSE(std::filesystem::exists(dir.file("out.pfm")));
      // Without emission the instances are one mesh placed 10000 times: refused at 2 MB naming
      // the instances, rendered in 8 MB.
      scene["meshes"][0].erase("emission");
      dir.write("scene.json", scene.dump());
      const CliResult small = render(dir.file("scene.json"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=2000000"});
      CHECK(small.exitCode == 2);
      CHECK(oneLine(small.err));
      CHECK(small.err.find(dir.file("scene.json") + ": meshes[0].instances: placing the mesh gives 10000 instances") !=
            std::string::npos);
      const CliResult kept = render(dir.file("scene.json"), dir.file("out.pfm"), {"MONTECL_MEMORY_LIMIT=8000000"});
      CHECK_MESSAGE(kept.exitCode == 0, kept.err);
    }
  }
}

TEST_CASE("instancing: a scene file's instances, flattened, equal one mesh entry per transform, bit for bit" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("tent.obj", montecl_test::objText(montecl_test::tentMesh()));
  const json transforms = json::array({json{{"translate", {0.5, 0, -1}}},
                                       json{{"rotate", {0, 1, 0.5, 37}}, {"scale", {1.5, 0.5, -1}}, {"translate", {-1, 0.25, 0}}},
                                       json{{"matrix", {0.5, 0.1, 0, 2, 0, 1, 0.2, 0, 0, 0, 1, -3, 0, 0, 0, 1}}}});
  const json camera = {{"position", {1, 3, 6}}, {"target", {0, 0, -1}}, {"fov_y", 60}, {"width", 16}, {"height", 12}};
  const json render = {{"integrator", "direct"}, {"spp", 2}};
  json lights = json::array({json{{"type", "point"}, {"position", {0, 4, 2}}, {"intensity", {20, 20, 20}}}});
  json inst = {{"camera", camera}, {"render", render}, {"lights", lights},
               {"meshes", {{{"file", "tent.obj"}, {"material", {{"albedo", {0.6, 0.3, 0.2}}}}, {"instances", transforms}}}}};
  json separate = {{"camera", camera}, {"render", render}, {"lights", lights}, {"meshes", json::array()}};
  for (const json& t : transforms)
    separate["meshes"].push_back({{"file", "tent.obj"}, {"material", {{"albedo", {0.6, 0.3, 0.2}}}}, {"transform", t}});
  dir.write("inst.json", inst.dump());
  dir.write("separate.json", separate.dump());
  std::vector<std::string> w;
  const Scene kept = montecl::loadScene(dir.file("inst.json"), w), b = montecl::loadScene(dir.file("separate.json"), w);
  CHECK(kept.triangles.size() == 4);  // one mesh, placed three times
  CHECK(kept.instances.size() == 3);
  Scene a = kept;
  montecl::flattenInstances(a);
  CHECK(a.triangles.size() == 3 * 4);
  checkSameTriangles(a, b);
  CHECK(a.materials.size() < b.materials.size());  // the copies share the entry's material
  const CliResult ra = runMontecl({"render", dir.file("inst.json"), "-o", dir.file("inst.pfm"), "-q", "--device", "host"});
  const CliResult rb = runMontecl({"render", dir.file("separate.json"), "-o", dir.file("separate.pfm"), "-q", "--device", "host"});
  REQUIRE_MESSAGE(ra.exitCode == 0, ra.err);
  REQUIRE_MESSAGE(rb.exitCode == 0, rb.err);
  // With the entry's transform too, each copy is instance x transform.
  inst["meshes"][0]["transform"] = {{"scale", 2}};
  dir.write("inst2.json", inst.dump());
  Scene c = montecl::loadScene(dir.file("inst2.json"), w);
  montecl::flattenInstances(c);
  REQUIRE(c.triangles.size() == a.triangles.size());
  CHECK(c.triangles[0].v[0] == a.triangles[0].v[0] + a.triangles[0].v[0] - glm::vec3(0.5f, 0.0f, -1.0f));
  // Bad lists: one line naming the key.
  for (const auto& bad : {std::make_pair(json::array(), std::string("meshes[0].instances: expected a non-empty list")),
                          std::make_pair(json::array({json{{"translate", {0, 0, 0}}}, json{{"scale", 0}}}),
                                         std::string("meshes[0].instances[1].scale: must not be 0"))}) {
    json j = inst;
    j["meshes"][0]["instances"] = bad.first;
    dir.write("bad.json", j.dump());
    const CliResult r = runMontecl({"render", dir.file("bad.json"), "-o", dir.file("bad.pfm"), "-q", "--device", "host"});
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(dir.file("bad.json") + ": " + bad.second) != std::string::npos);
  }
}

}  // namespace test_file_instancing
