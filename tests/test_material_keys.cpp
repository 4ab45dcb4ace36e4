// test_material_keys.cpp: the material kinds' scene keys and loader mappings: a scene file's
// conductor / dielectric / metal_rough keys land in MaterialDesc (a metal name picks its RGB eta,
// k; roughness squares into alpha; the conductor's distribution and specular_reflectance), bad values exit 2 through the CLI with one line naming the key
// and write no output; MTL illum 7 + Ni -> dielectric (no 'Ni'/'illum' warning), Pm / Pr ->
// metal_rough; glTF metallic/roughness factors -> metal_rough, the (1, 1) defaults stay diffuse.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/scene.h"

namespace test_file_material_keys {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {

const char* kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

std::string sceneWith(const TempDir& dir, const std::string& material) {
  dir.write("tri.obj", kTri);
  dir.write("scene.json", R"({"camera": {"position": [0.3, 0.3, 2], "target": [0.3, 0.3, 0], "fov_y": 40, "width": 4, "height": 4},
    "meshes": [{"file": "tri.obj", "material": )" + material + "}]}");
  return dir.file("scene.json");
}

}  // namespace

TEST_CASE("material keys: conductor metal / roughness, dielectric ior, metal_rough factors reach MaterialDesc" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  std::vector<std::string> warnings;
  Scene s = loadScene(sceneWith(dir, R"({"type": "conductor", "metal": "Cu", "roughness": 0.5})"), warnings);
  REQUIRE(s.materials.size() >= 1);
  const MaterialDesc& c = s.materials.back();
  CHECK(c.kind == std::uint32_t(MCL_MATERIAL_conductor));
  CHECK(c.eta.x == doctest::Approx(0.201005f));
  CHECK(c.k.z == doctest::Approx(2.14209f));
  CHECK(c.kindAlpha == doctest::Approx(0.25f));
  CHECK(!c.beckmann);  // GGX unless asked
  CHECK(c.conductorFactor == glm::vec3(1.0f));
  s = loadScene(sceneWith(dir, R"({"type": "conductor", "metal": "Cu", "alpha": 0.1, "distribution": "beckmann",
                                   "specular_reflectance": [0.3, 0.3, 0.3]})"), warnings);
  CHECK(s.materials.back().beckmann);
  CHECK(s.materials.back().conductorFactor == glm::vec3(0.3f));
  s = loadScene(sceneWith(dir, R"({"type": "dielectric", "ior": 1.33})"), warnings);
  CHECK(s.materials.back().kind == std::uint32_t(MCL_MATERIAL_dielectric));
  CHECK(s.materials.back().ior == doctest::Approx(1.33f));
  s = loadScene(sceneWith(dir, R"({"type": "metal_rough", "metallic": 0.7, "roughness": 0.2, "albedo": [0.9, 0.5, 0.1]})"),
                warnings);
  CHECK(s.materials.back().kind == std::uint32_t(MCL_MATERIAL_metal_rough));
  CHECK(s.materials.back().metallic == doctest::Approx(0.7f));
  CHECK(s.materials.back().roughness == doctest::Approx(0.2f));
}

TEST_CASE("material keys: bad values exit 2 with one line naming the key, no output" * doctest::test_suite("cli sanitize")) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"({"type": "dielectric", "ior": 0})", "material.ior"},
      {R"({"type": "dielectric", "ior": -1.5})", "material.ior"},
      {R"({"type": "dielectric", "ior": 1e999})", "material.ior"},
      {R"({"type": "conductor", "alpha": 1.5})", "material.alpha"},
      {R"({"type": "conductor", "alpha": 0.1, "roughness": 0.3})", "material.roughness"},
      {R"({"type": "metal_rough", "metallic": 2})", "material.metallic"},
      {R"({"type": "metal_rough", "roughness": -0.1})", "material.roughness"},
      {R"({"type": "glass"})", "material.type"},
      {R"({"type": "conductor", "metal": "Pt"})", "material.metal"},
      {R"({"type": "conductor", "metal": "Au", "eta": [1, 1, 1]})", "material.eta"},
      {R"({"type": "conductor", "distribution": "phong"})", "material.distribution"},
      {R"({"type": "conductor", "specular_reflectance": [0.3, -1, 0.3]})", "material.specular_reflectance"},
      {R"({"type": "metal_rough", "sheen_color": [0.5, 1.5, 0.5]})", "material.sheen_color: components must be in [0, 1]"},
      {R"({"type": "metal_rough", "sheen_color": [0.5, 0.5]})", "material.sheen_color"},
      {R"({"type": "metal_rough", "sheen_roughness": 2})", "material.sheen_roughness: must be in [0, 1]"},
  };
  for (const auto& row : bad) {
    const auto& material = std::get<0>(row);
    const auto& key = std::get<1>(row);
    CAPTURE(material);
    TempDir dir;
    const CliResult r = runMontecl({"render", sceneWith(dir, material), "-q", "-o", dir.file("out.pfm")});
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(key) != std::string::npos);
    CHECK(r.err.find("scene.json") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.out.empty());
    CHECK_FALSE(std::ifstream(dir.file("out.pfm")).good());
  }
}

TEST_CASE("material keys: MTL illum 7 + Ni is a dielectric, Pm / Pr metal_rough; glTF factors metal_rough" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("m.mtl", "newmtl glass\nillum 7\nNi 1.4\nnewmtl pbr\nKd 0.8 0.6 0.2\nPm 1\nPr 0.3\n"
                     "newmtl plain\nKd 0.5 0.5 0.5\nillum 2\nNi 1.5\n");
  dir.write("m.obj", std::string("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n") +
                         "usemtl glass\nf 1 2 3\nusemtl pbr\nf 2 4 3\nusemtl plain\nf 1 3 4\n");
  std::vector<std::string> warnings;
  Scene s = loadScene(dir.file("m.obj"), warnings);
  REQUIRE(s.materials.size() == 3);
  CHECK(s.materials[0].kind == std::uint32_t(MCL_MATERIAL_dielectric));
  CHECK(s.materials[0].ior == doctest::Approx(1.4f));
  CHECK(s.materials[1].kind == std::uint32_t(MCL_MATERIAL_metal_rough));
  CHECK(s.materials[1].metallic == 1.0f);
  CHECK(s.materials[1].roughness == doctest::Approx(0.3f));
  CHECK(s.materials[2].kind == std::uint32_t(MCL_MATERIAL_diffuse));
  CHECK(countContaining(warnings, "'illum'") == 1);  // the plain material's, only
  CHECK(countContaining(warnings, "line 10") == 1);
  CHECK(countContaining(warnings, "'Pm'") == 0);
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  dir.write("t.bin", montecl_test::gltfBuffer(tent));
  const std::string gltf = montecl_test::gltfText(tent, 0.5f, "t.bin");
  const std::string written = R"(,"metallicFactor":0,"roughnessFactor":1)";
  REQUIRE(gltf.find(written) != std::string::npos);
  // glTF's defaults (1, 1), given or left out, are a rough metal; only (0, 1) stays Lambertian.
  for (const auto& row : std::vector<std::pair<std::string, std::uint32_t>>{
           {"", MCL_MATERIAL_metal_rough},
           {R"(,"metallicFactor":1,"roughnessFactor":1)", MCL_MATERIAL_metal_rough},
           {written, MCL_MATERIAL_diffuse},
           {R"(,"metallicFactor":1,"roughnessFactor":0.4)", MCL_MATERIAL_metal_rough},
           {R"(,"metallicFactor":0,"roughnessFactor":0.5)", MCL_MATERIAL_metal_rough}}) {
    const auto& factors = std::get<0>(row);
    const auto& kind = std::get<1>(row);
    CAPTURE(factors);
    std::string text = gltf;
    text.replace(text.find(written), written.size(), factors);
    dir.write("t.gltf", text);
    warnings.clear();
    s = loadScene(dir.file("t.gltf"), warnings);
    CHECK(s.materials.back().kind == kind);
    CHECK(countContaining(warnings, "metallic") == 0);
  }
}

}  // namespace test_file_material_keys
