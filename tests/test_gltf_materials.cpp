// test_gltf_materials.cpp: glTF materials as the specification defines them
// (host/scene/gltf_material.cpp): the default factors (1, 1), given or not, and a primitive without
// a material are glTF's rough metal (the loaded MaterialDesc, and a render bit-identical to the
// scene file's metal_rough of those factors); KHR_materials_pbrSpecularGlossiness converted to
// metal/rough on load (closed forms: a metal/rough material turned into specular-glossiness and
// back is itself; a black-diffuse coloured specular is a metal of that colour; the specular map
// converted texel by texel), no longer refused when required; KHR_materials_specular's factor 0 on
// a dielectric is Lambert (bit-identical to the (0, 1) material), other values warned.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "kernels/shared/texture.h"
#include "mesh_files.h"
#include "scene_renders.h"
#include "scene/gltf_spec_gloss.h"
#include "test_images.h"
#include "texture/scene_textures.h"
#include "util/errors.h"

namespace test_file_gltf_materials {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// The tent as glTF, its material 0 replaced by `material` (null: no material at all).
std::string tentWith(const nlohmann::json& material) {
  nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), 0.5f, ""));
  if (material.is_null()) {
    g.erase("materials");
    g["meshes"][0]["primitives"][0].erase("material");
  } else {
    g["materials"][0] = material;
    if (material.contains("extensions"))
      for (auto it = material["extensions"].begin(); it != material["extensions"].end(); ++it)
        g["extensionsUsed"].push_back(it.key());
  }
  return g.dump();
}

// The tent under a constant environment and a directional light, path traced, seen from above
// (as test_gltf_transmission's scenes), with an optional material override.
std::string sceneText(const std::string& gltf, const nlohmann::json& material) {
  nlohmann::json s = {{"camera", {{"position", {1.2, 3.5, -1}}, {"target", {1.2, 0, -1}}, {"up", {0, 0, -1}},
                                  {"fov_y", 45}, {"width", 12}, {"height", 10}}},
                      {"meshes", {{{"file", gltf}}}},
                      {"environment", {{"radiance", {0.3, 0.2, 0.1}}}},
                      {"lights", {{{"type", "directional"}, {"direction", {0.3, -1, 0.2}}, {"irradiance", {2, 2, 2}}}}},
                      {"render", {{"integrator", "path"}, {"spp", 8}, {"max_depth", 4}}}};
  if (!material.is_null()) s["meshes"][0]["material"] = material;
  return s.dump();
}

Scene load(const TempDir& dir, const std::string& name, const std::string& text, std::vector<std::string>& warnings) {
  dir.write(name, text);
  warnings.clear();
  return loadScene(dir.file(name), warnings);
}

}  // namespace

TEST_CASE("glTF default factors (1, 1) and no material: glTF's rough metal, as the scene file's metal_rough" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  std::vector<std::string> warnings;
  const nlohmann::json red = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.1, 0.1, 1}}}}};
  const Scene defaults = load(dir, "red.gltf", tentWith(red), warnings);
  REQUIRE(defaults.materials.size() == 1);
  CHECK(defaults.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(defaults.materials[0].metallic == 1.0f);
  CHECK(defaults.materials[0].roughness == 1.0f);
  CHECK(defaults.materials[0].albedo == glm::vec3(0.8f, 0.1f, 0.1f));
  // No material: glTF's default material, white, metallic 1, roughness 1 (not the grey Lambert).
  const Scene bare = load(dir, "bare.gltf", tentWith(nullptr), warnings);
  REQUIRE(bare.materials.size() == 1);
  CHECK(bare.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(bare.materials[0].albedo == glm::vec3(1.0f));
  CHECK(bare.materials[0].metallic == 1.0f);
  CHECK(bare.materials[0].roughness == 1.0f);
  // Rendered, each is the scene file's metal_rough with those factors, bit for bit; not Lambert.
  dir.write("red.json", sceneText("red.gltf", nullptr));
  dir.write("red-ref.json", sceneText("red.gltf", {{"type", "metal_rough"}, {"albedo", {0.8, 0.1, 0.1}}, {"metallic", 1}, {"roughness", 1}}));
  dir.write("red-lambert.json", sceneText("red.gltf", {{"type", "diffuse"}, {"albedo", {0.8, 0.1, 0.1}}}));
  dir.write("bare.json", sceneText("bare.gltf", nullptr));
  dir.write("bare-ref.json", sceneText("bare.gltf", {{"type", "metal_rough"}, {"albedo", {1, 1, 1}}, {"metallic", 1}, {"roughness", 1}}));
  const Film redFilm = renderSceneFile(dir.file("red.json"));
  CHECK(sameMeanBits(redFilm, renderSceneFile(dir.file("red-ref.json"))));
  CHECK_FALSE(sameMeanBits(redFilm, renderSceneFile(dir.file("red-lambert.json"))));
  CHECK(sameMeanBits(renderSceneFile(dir.file("bare.json")), renderSceneFile(dir.file("bare-ref.json"))));
}

// The conversion's closed forms: metal/rough (grey base b, metallic m) as specular-glossiness is
// specular = mix(0.04, b, m) and diffuse = b (1 - 0.04)(1 - m) / (1 - specular) (the extension's
// diffuse is scaled by 1 - max(specular)): converted back it is (b, m) again; a black diffuse with
// a coloured specular at or above 0.04 is a metal (metallic 1) of exactly that colour.
TEST_CASE("glTF specular-glossiness factors: metal/rough and back is the identity; a coloured specular is a metal" *
          doctest::test_suite("cpu")) {
  for (float m : {0.0f, 0.25f, 0.6f, 1.0f})
    for (float b : {0.1f, 0.5f, 0.9f}) {
      CAPTURE(m);
      CAPTURE(b);
      const float specular = 0.04f * (1.0f - m) + b * m;
      const float diffuse = b * 0.96f * (1.0f - m) / (1.0f - specular);
      const MetalRoughFactors r = metalRoughFromSpecGloss(glm::vec3(diffuse), glm::vec3(specular), 0.7f);
      CHECK(r.metallic == doctest::Approx(m).epsilon(1e-4));
      CHECK(r.base.g == doctest::Approx(b).epsilon(1e-4));
      CHECK(r.roughness == doctest::Approx(0.3f));
    }
  const glm::vec3 gold(1.0f, 0.766f, 0.336f);
  const MetalRoughFactors metal = metalRoughFromSpecGloss(glm::vec3(0.0f), gold, 1.0f);
  CHECK(metal.metallic == doctest::Approx(1.0f));
  for (int c = 0; c < 3; ++c) CHECK(metal.base[c] == doctest::Approx(gold[c]).epsilon(1e-5));
  CHECK(metal.roughness == 0.0f);
  // Below the dielectric 0.04 nothing is metal: the diffuse colour, rescaled, is the base.
  const MetalRoughFactors plastic = metalRoughFromSpecGloss(glm::vec3(0.5f, 0.2f, 0.1f), glm::vec3(0.02f), 0.0f);
  CHECK(plastic.metallic == 0.0f);
  CHECK(plastic.base.r == doctest::Approx(0.5f * 0.98f / 0.96f));
  CHECK(plastic.roughness == 1.0f);
}

TEST_CASE("glTF KHR_materials_pbrSpecularGlossiness: converted on load (warned), read even when required" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  std::vector<std::string> warnings;
  const float m = 0.6f, b = 0.5f, specular = 0.04f * (1.0f - m) + b * m, diffuse = b * 0.96f * (1.0f - m) / (1.0f - specular);
  const nlohmann::json sg = {{"diffuseFactor", {diffuse, diffuse, diffuse, 1}},
                             {"specularFactor", {specular, specular, specular}},
                             {"glossinessFactor", 0.8}};
  nlohmann::json g = nlohmann::json::parse(tentWith({{"extensions", {{"KHR_materials_pbrSpecularGlossiness", sg}}}}));
  g["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
  const Scene s = load(dir, "sg.gltf", g.dump(), warnings);
  REQUIRE(s.materials.size() == 1);
  const MaterialDesc& d = s.materials[0];
  CHECK(d.kind == MCL_MATERIAL_metal_rough);
  CHECK(d.metallic == doctest::Approx(m).epsilon(1e-4));
  CHECK(d.roughness == doctest::Approx(0.2f));
  CHECK(d.albedo.r == doctest::Approx(b).epsilon(1e-4));
  CHECK_FALSE(d.specGlossMap);
  CHECK(countContaining(warnings, "KHR_materials_pbrSpecularGlossiness converted to metallic-roughness on load: an approximation") == 1);
  CHECK(countContaining(warnings, "not used by montecl") == 0);
  // A bad factor is one line naming it.
  nlohmann::json bad = sg;
  bad["glossinessFactor"] = 2;
  dir.write("bad.gltf", tentWith({{"extensions", {{"KHR_materials_pbrSpecularGlossiness", bad}}}}));
  std::string error;
  try {
    loadScene(dir.file("bad.gltf"), warnings);
  } catch (const InputError& e) {
    error = e.what();
  }
  CHECK(error.find("materials[0].extensions.KHR_materials_pbrSpecularGlossiness.glossinessFactor: must be in [0, 1]") !=
        std::string::npos);
}

// The specular-glossiness map, texel by texel: roughness = 1 - alpha x glossinessFactor, and the
// metallic of the texel's specular (x specularFactor) with the diffuseFactor's colour; the diffuse
// texture is the base colour texture.
TEST_CASE("glTF specularGlossinessTexture: each texel converted to metallic-roughness by the texture loader" *
          doctest::test_suite("cpu")) {
  // Closed forms of one texel: a dielectric's (specular 0.04 or less: metallic 0) and a metal's.
  const glm::vec4 dielectric = specGlossTexel(glm::vec4(0.02f, 0.02f, 0.02f, 0.5f), glm::vec4(1, 1, 1, 0.8f), glm::vec3(1.0f));
  CHECK(dielectric.x == 0.0f);
  CHECK(dielectric.y == doctest::Approx(1.0f - 0.5f * 0.8f));
  CHECK(dielectric.z == 0.0f);
  CHECK(dielectric.w == 1.0f);
  const glm::vec4 metal = specGlossTexel(glm::vec4(0.9f, 0.9f, 0.9f, 1.0f), glm::vec4(1.0f), glm::vec3(0.0f));
  CHECK(metal.y == 0.0f);
  CHECK(metal.z == doctest::Approx(1.0f));
  // Through the loaders: an 8-bit map, specular black (metallic 0), alpha 191 (glossiness 0.749).
  TempDir dir;
  writeImage8(dir.file("sg.png"), 4, 4, 4, [](int, int, int c) { return c == 3 ? 191 : 0; });
  writeImage8(dir.file("diffuse.png"), 4, 4, 3, [](int x, int, int) { return 40 * x; });
  nlohmann::json g = nlohmann::json::parse(tentWith(
      {{"extensions", {{"KHR_materials_pbrSpecularGlossiness",
                        {{"diffuseTexture", {{"index", 1}}}, {"specularGlossinessTexture", {{"index", 0}}}, {"glossinessFactor", 0.5}}}}}}));
  g["images"] = {{{"uri", "sg.png"}}, {{"uri", "diffuse.png"}}};
  g["textures"] = {{{"source", 0}}, {{"source", 1}}};
  std::vector<std::string> warnings;
  const Scene s = load(dir, "sg.gltf", g.dump(), warnings);
  REQUIRE(s.materials.size() == 1);
  const MaterialDesc& d = s.materials[0];
  CHECK(d.kind == MCL_MATERIAL_metal_rough);
  CHECK(d.specGlossMap);
  CHECK(d.metallicRoughnessTexture == dir.file("sg.png"));
  CHECK(d.albedoTexture == dir.file("diffuse.png"));
  CHECK(d.metallic == 1.0f);  // the texels hold the values
  CHECK(d.roughness == 1.0f);
  CHECK(d.specGloss.w == 0.5f);
  const SceneTextures st = loadSceneTextures(s, kDefaultTextureBudget, warnings);
  REQUIRE(st.materials[0].metallicRoughness != MCL_NO_TEXTURE);
  const TextureLevel l = st.levels[st.textures[st.materials[0].metallicRoughness].firstLevel];
  const TextureTables tt{st.textures.data(), st.levels.data(), st.texels.data()};
  const float4 t = texel_at(tt, l, 0, 0);  // as the kernels read it
  CHECK(t.y == doctest::Approx(1.0f - 0.5f * 191.0f / 255.0f).epsilon(1e-3));
  CHECK(t.z == 0.0f);
}

TEST_CASE("glTF KHR_materials_specular: factor 0 on a dielectric is Lambert, bit for bit; other values warned" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  std::vector<std::string> warnings;
  const auto material = [](double metallic, double roughness, const nlohmann::json& specular) {
    nlohmann::json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.5, 0.3, 1}}, {"metallicFactor", metallic},
                                                  {"roughnessFactor", roughness}}}};
    if (!specular.is_null()) m["extensions"] = {{"KHR_materials_specular", specular}};
    return m;
  };
  const Scene none = load(dir, "none.gltf", tentWith(material(0.0, 0.4, {{"specularFactor", 0}})), warnings);
  CHECK(none.materials[0].kind == MCL_MATERIAL_diffuse);
  CHECK(none.materials[0].albedo == glm::vec3(0.7f, 0.5f, 0.3f));
  CHECK(countContaining(warnings, "KHR_materials_specular") == 0);
  load(dir, "lambert.gltf", tentWith(material(0.0, 1.0, nullptr)), warnings);
  dir.write("none.json", sceneText("none.gltf", nullptr));
  dir.write("lambert.json", sceneText("lambert.gltf", nullptr));
  CHECK(sameMeanBits(renderSceneFile(dir.file("none.json")), renderSceneFile(dir.file("lambert.json"))));
  // The defaults change nothing; a metal, or another factor, keeps metal_rough and says so.
  const Scene defaults = load(dir, "d.gltf", tentWith(material(0.0, 0.4, {{"specularFactor", 1}})), warnings);
  CHECK(defaults.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(countContaining(warnings, "KHR_materials_specular") == 0);
  const Scene metal = load(dir, "m.gltf", tentWith(material(0.5, 0.4, {{"specularFactor", 0}})), warnings);
  CHECK(metal.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(countContaining(warnings, "KHR_materials_specular not used here") == 1);
  load(dir, "c.gltf", tentWith(material(0.0, 0.4, {{"specularColorFactor", {1, 0.5, 0.5}}})), warnings);
  CHECK(countContaining(warnings, "KHR_materials_specular not used here") == 1);
}

}  // namespace test_file_gltf_materials
