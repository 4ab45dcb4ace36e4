// test_metal_rough_texture.cpp: glTF metallicRoughnessTexture on the metal_rough kind
// (kernels/shared/surface_texture.h hit_metal_rough: B x metallic, G x roughness): the loader makes
// the kind and reads the texture linear (8-bit 128 -> 128/255, not sRGB-decoded); a quad under a
// constant environment renders as the factors the texture implies (B = 0 as metallic 0, B = 255
// as metallic 1: z-tests of the image means) and differently from the other.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "kernels/shared/texture.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "scene_renders.h"
#include "test_images.h"
#include "test_scenes.h"
#include "texture/scene_textures.h"
#include "util/errors.h"

namespace test_file_metal_rough_texture {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// A quad facing the camera, metal_rough with base colour (0.8, 0.3, 0.2), under a constant
// environment of radiance 1 (direct lighting, MIS).
Scene quad(float metallic, float roughness, const std::string& texture) {
  Scene s;
  s.path = "<metal_rough quad>";
  MaterialDesc m("mr", glm::vec3(0.8f, 0.3f, 0.2f));
  m.kind = MCL_MATERIAL_metal_rough;
  m.metallic = metallic;
  m.roughness = roughness;
  m.metallicRoughnessTexture = texture;
  s.materials = {m};
  const glm::vec3 a(-1, -1, 0), b(1, -1, 0), c(1, 1, 0), d(-1, 1, 0);
  s.triangles.push_back(SceneTriangle{{a, b, c}, 0, {}, {{0, 0}, {1, 0}, {1, 1}}, kHasUv});
  s.triangles.push_back(SceneTriangle{{a, c, d}, 0, {}, {{0, 0}, {1, 1}, {0, 1}}, kHasUv});
  s.camera.position = {0.3f, 0.2f, 2.5f};
  s.camera.target = {0, 0, 0};
  s.camera.fovY = 30.0f;
  s.camera.width = s.camera.height = 8;
  s.render.spp = 256;
  s.render.integrator = Integrator::Direct;
  s.environment.enabled = true;
  finishScene(s);
  return s;
}

Film render(const Scene& s, std::uint32_t seed) {
  Scene c = s;
  c.render.seed = seed;
  c.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  Bvh bvh = buildBvh(c.triangles);
  WavefrontRenderer r(hostDeviceInfo(), {});
  RenderStats stats;
  return r.render(c, bvh, stats);
}

double z(const Film& a, const Film& b, int c) {
  const ImageEstimate ea = imageEstimate(a, c), eb = imageEstimate(b, c);
  return (ea.mean - eb.mean) / std::hypot(ea.standardError, eb.standardError);
}

}  // namespace

TEST_CASE("metallicRoughnessTexture: glTF makes metal_rough and the texture is read linear" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("mr.png"), 4, 4, 3, [](int, int, int c) { return c == 0 ? 0 : 128; });
  nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), 0.5f, ""));
  g["images"] = {{{"uri", "mr.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}};
  dir.write("m.gltf", g.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("m.gltf"), warnings);
  for (const std::string& w : warnings) CHECK(w.find("metallicRoughnessTexture") == std::string::npos);
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].kind == MCL_MATERIAL_metal_rough);  // the default factors (1, 1) x the texture
  CHECK(s.materials[0].metallicRoughnessTexture == dir.file("mr.png"));
  const SceneTextures st = loadSceneTextures(s, kDefaultTextureBudget, warnings);
  REQUIRE(st.materials[0].metallicRoughness != MCL_NO_TEXTURE);
  const TextureLevel l = st.levels[st.textures[st.materials[0].metallicRoughness].firstLevel];
  const TextureTables tt{st.textures.data(), st.levels.data(), st.texels.data()};
  const float g0 = texel_at(tt, l, 0, 0).y;  // as the kernels read it (half, or an 8-bit code's decode)
  CHECK(std::fabs(g0 - 128.0f / 255.0f) < 1e-3f);  // linear, not 0.2158
}

TEST_CASE("metallicRoughnessTexture: B scales metallic and G roughness in the render" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("dielectric.png"), 4, 4, 3, [](int, int, int c) { return c == 1 ? 255 : 0; });  // G 1, B 0
  writeImage8(dir.file("metal.png"), 4, 4, 3, [](int, int, int c) { return c == 0 ? 0 : 255; });       // G 1, B 1
  const Film texDielectric = render(quad(1.0f, 0.5f, dir.file("dielectric.png")), 1);
  const Film plainDielectric = render(quad(0.0f, 0.5f, ""), 2);
  const Film texMetal = render(quad(1.0f, 0.5f, dir.file("metal.png")), 3);
  const Film plainMetal = render(quad(1.0f, 0.5f, ""), 4);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    CHECK(std::fabs(z(texDielectric, plainDielectric, c)) < 4.0);
    CHECK(std::fabs(z(texMetal, plainMetal, c)) < 4.0);
  }
  CHECK(std::fabs(z(texDielectric, texMetal, 0)) > 10.0);  // the texture matters
}

namespace {

std::string sceneAround(const std::string& mesh, const nlohmann::json& material) {
  nlohmann::json s = {{"camera", {{"position", {1.2, 3.5, -1}}, {"target", {1.2, 0, -1}}, {"up", {0, 0, -1}},
                                  {"fov_y", 45}, {"width", 12}, {"height", 10}}},
                      {"meshes", {{{"file", mesh}}}},
                      {"environment", {{"radiance", {0.9, 0.8, 0.7}}}},
                      {"render", {{"integrator", "direct"}, {"spp", 16}}}};
  if (!material.is_null()) s["meshes"][0]["material"] = material;
  return s.dump();
}

}  // namespace

// The scene file's "metallic_roughness_texture" is glTF's metallicRoughnessTexture: a mesh given
// the texture and factors in the scene file renders bit-identically to the glTF that carries them.
TEST_CASE("metallic_roughness_texture: the scene-file key equals the glTF texture, bit for bit" * doctest::test_suite("cpu")) {
  TempDir dir;
  // B (metallic) runs across the image, G (roughness) down it.
  writeImage8(dir.file("mr.png"), 8, 8, 3, [](int x, int y, int c) { return c == 0 ? 0 : c == 1 ? 32 * y : 32 * x; });
  nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), 0.7f, ""));
  g["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 0.9;
  g["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 0.8;
  dir.write("plain.gltf", g.dump());
  g["images"] = {{{"uri", "mr.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}};
  dir.write("textured.gltf", g.dump());
  dir.write("gltf.json", sceneAround("textured.gltf", nullptr));
  dir.write("key.json", sceneAround("plain.gltf", {{"type", "metal_rough"}, {"metallic", 0.9}, {"roughness", 0.8},
                                                   {"metallic_roughness_texture", "mr.png"}}));
  dir.write("factors.json", sceneAround("plain.gltf", nullptr));
  std::vector<std::string> warnings;
  const Scene key = loadScene(dir.file("key.json"), warnings);
  REQUIRE(key.materials.size() == 2);  // the file's and the override's copy
  CHECK(key.materials[1].metallicRoughnessTexture == dir.file("mr.png"));
  const Film viaGltf = renderSceneFile(dir.file("gltf.json"));
  CHECK(sameMeanBits(viaGltf, renderSceneFile(dir.file("key.json"))));
  CHECK_FALSE(sameMeanBits(viaGltf, renderSceneFile(dir.file("factors.json"))));  // the texture matters
  // Only metal_rough reads it; a missing file is refused too.
  dir.write("conductor.json", sceneAround("plain.gltf", {{"type", "conductor"}, {"metallic_roughness_texture", "mr.png"}}));
  dir.write("missing.json", sceneAround("plain.gltf", {{"type", "metal_rough"}, {"metallic_roughness_texture", "no.png"}}));
  for (const char* bad : {"conductor.json", "missing.json"}) {
    CAPTURE(bad);
    std::string what;
    try {
      loadScene(dir.file(bad), warnings);
    } catch (const InputError& e) {
      what = e.what();
    }
    CHECK(what.find("meshes[0].material.metallic_roughness_texture") != std::string::npos);
  }
}

}  // namespace test_file_metal_rough_texture
