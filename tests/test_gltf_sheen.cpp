// test_gltf_sheen.cpp: glTF KHR_materials_sheen onto metal_rough's sheen (host/scene/gltf_sheen.cpp,
// kernels/shared/sheen.h, bsdf_metal_rough.h): the file's sheen renders bit-identically to the scene
// file's sheen keys, colour 0 to the plain material; a file that requires the extension loads; what
// is not modelled is warned; bad values are one line naming the key; a coloured sheen over a smooth
// black base under a white sky renders its closed form per channel (z-test); the packet stages shade
// sheened and plain hits in one packet byte for byte as the host backend does at W = 1, 4, 8, 16,
// all in lane types.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "charlie_sheen.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "kernels/shared/sheen.h"
#include "lanes_vs_host.h"
#include "gltf_extension_scenes.h"
#include "mesh_files.h"
#include "scene_renders.h"
#include "util/errors.h"

namespace test_file_gltf_sheen {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// The tent mesh as glTF (a blue base of the given factors) with the material extensions `ext`.
std::string sheenGltf(float metallic, float roughness, const nlohmann::json& ext) {
  return tentGltf(nlohmann::json::array({0.1, 0.15, 0.6, 1.0}), metallic, roughness, ext);
}

nlohmann::json sheenExt(const nlohmann::json& color, const nlohmann::json& roughness) {
  return {{"KHR_materials_sheen", {{"sheenColorFactor", color}, {"sheenRoughnessFactor", roughness}}}};
}

// The scene looking at the tent (gltf_extension_scenes.h).
std::string sceneText(const std::string& gltf, const nlohmann::json& material, const nlohmann::json& second = nullptr) {
  return tentSceneText(gltf, material, second);
}


}  // namespace

TEST_CASE("glTF sheen: the file's sheen is the scene file's sheen keys bit for bit; colour 0 is no sheen" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("plain.gltf", sheenGltf(0.0f, 0.6f, nullptr));
  dir.write("sheen.gltf", sheenGltf(0.0f, 0.6f, sheenExt({0.9, 0.7, 0.5}, 0.4)));
  dir.write("off.gltf", sheenGltf(0.0f, 0.6f, sheenExt({0, 0, 0}, 0.5)));
  dir.write("sheen.json", sceneText("sheen.gltf", nullptr));
  dir.write("off.json", sceneText("off.gltf", nullptr));
  dir.write("plain.json", sceneText("plain.gltf", nullptr));
  const auto keys = [](const nlohmann::json& color, double rough) {
    return nlohmann::json{{"type", "metal_rough"}, {"albedo", {0.1, 0.15, 0.6}}, {"metallic", 0}, {"roughness", 0.6},
                          {"sheen_color", color}, {"sheen_roughness", rough}};
  };
  dir.write("keys.json", sceneText("plain.gltf", keys({0.9, 0.7, 0.5}, 0.4)));
  dir.write("rougher.json", sceneText("plain.gltf", keys({0.9, 0.7, 0.5}, 0.44)));
  dir.write("bluer.json", sceneText("plain.gltf", keys({0.9, 0.7, 0.55}, 0.4)));
  const Film sheen = renderSceneFile(dir.file("sheen.json")), plain = renderSceneFile(dir.file("plain.json"));
  CHECK(sameMeanBits(sheen, renderSceneFile(dir.file("keys.json"))));
  CHECK_FALSE(sameMeanBits(sheen, renderSceneFile(dir.file("rougher.json"))));  // the roughness is read
  CHECK_FALSE(sameMeanBits(sheen, renderSceneFile(dir.file("bluer.json"))));    // and the colour's b
  CHECK_FALSE(sameMeanBits(sheen, plain));                                    // and the sheen shows
  CHECK(sameMeanBits(plain, renderSceneFile(dir.file("off.json"))));
}

TEST_CASE("glTF sheen: a file requiring it loads; the (0, 1) pair becomes metal_rough; what is left out is warned" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  nlohmann::json ext = sheenExt({1.0, 0.5, 0.25}, 0.3);
  ext["KHR_materials_sheen"]["sheenColorTexture"] = {{"index", 0}};
  nlohmann::json g = nlohmann::json::parse(sheenGltf(0.0f, 1.0f, ext));
  g["extensionsRequired"] = {"KHR_materials_sheen"};
  dir.write("req.gltf", g.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("req.gltf"), warnings);
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(s.materials[0].roughness == 1.0f);
  CHECK(s.materials[0].sheenColor == glm::vec3(1.0f, 0.5f, 0.25f));
  CHECK(s.materials[0].sheenRoughness == 0.3f);
  int textures = 0, ignored = 0;
  for (const std::string& w : warnings) {
    textures += w.find("sheenColorTexture and sheenRoughnessTexture not read") != std::string::npos;
    ignored += w.find("KHR_materials_sheen' not used") != std::string::npos;
  }
  CHECK(textures == 1);
  CHECK(ignored == 0);
  // Only the roughness factor: the colour's default, 0, disables the layer (and the material stays diffuse).
  dir.write("rough.gltf", sheenGltf(0.0f, 1.0f, {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 0.5}}}}));
  const Scene r = loadScene(dir.file("rough.gltf"), warnings);
  CHECK(r.materials[0].kind == MCL_MATERIAL_diffuse);
  CHECK(r.materials[0].sheenColor == glm::vec3(0.0f));
}

TEST_CASE("glTF sheen: bad values are one line naming the key" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::pair<nlohmann::json, const char*> bad[] = {
      {sheenExt({1.5, 0, 0}, 0.0), "KHR_materials_sheen.sheenColorFactor: must be an array of 3 numbers in [0, 1]"},
      {sheenExt({0.5, -0.1, 0}, 0.0), "sheenColorFactor: must be an array of 3 numbers in [0, 1]"},
      {sheenExt({0.5, 0.5}, 0.0), "sheenColorFactor: must be an array of 3 numbers in [0, 1]"},
      {sheenExt(0.5, 0.0), "sheenColorFactor: must be an array of 3 numbers in [0, 1]"},
      {sheenExt({0.5, 0.5, 0.5}, 1.5), "KHR_materials_sheen.sheenRoughnessFactor: must be a number in [0, 1]"},
      {sheenExt({0.5, 0.5, 0.5}, "0.5"), "sheenRoughnessFactor: must be a number in [0, 1]"},
  };
  for (const auto& b : bad) {
    const std::string what = b.first.dump(), key = b.second;
    CAPTURE(what);
    dir.write("bad.gltf", sheenGltf(0.0f, 0.5f, b.first));
    const std::string e = sceneLoadError(dir.file("bad.gltf"));
    CHECK(e.find("bad.gltf: materials[0].extensions.") != std::string::npos);
    CHECK(e.find(key) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
  }
}

// A square facing the camera seen head-on through a 4-degree field of view (n.wo > 0.9993), a
// smooth black dielectric base (F0 0.04: Schlick's term is 0.04 to within 1e-16) under a sheen of
// colour c and roughness 1, in a sky of radiance 1 with nothing else: direct lighting (MIS of the
// sky's samples and the BSDF's) sees the one-bounce white furnace, per channel c_k E_true(1) + (1 -
// max(c) E(1)) 0.04, E_true the lobe's albedo (charlie_sheen.h's quadrature), E the kernel's fit.
// Channels apart tell a packing that moves the colour's components (the keys test cannot: glTF and
// the keys share the packing). Over the view's 0.0007 of n.wo, E_true moves by under 3e-4.
TEST_CASE("glTF sheen: a coloured sheen over a black base under a white sky renders c E + (1 - max(c) E) F (z-test)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  const double color[3] = {0.9, 0.5, 0.2};
  const std::string white = headOnWhiteSkyQuad(dir, sheenExt({color[0], color[1], color[2]}, 1.0));
  const Film f = renderSceneFile(white);
  const double eTrue = charlieAlbedo(1.0, 1.0), e = sheen_albedo(1.0f, 1.0f);
  for (int k = 0; k < 3; ++k) {
    const ImageEstimate est = imageEstimate(f, k);
    const double want = color[k] * eTrue + (1.0 - 0.9 * e) * 0.04;
    INFO("channel " << k << ": image mean " << est.mean << " +- " << est.standardError << ", closed form " << want
                    << " (E " << e << ", true " << eTrue << ")");
    CHECK(std::fabs(est.mean - want) <= 4.0 * est.standardError + 3e-4);
    CHECK(est.standardError < 0.01 * want);  // sharp enough to tell the channels (0.3 c E apart) apart
  }
}

// Two copies of the tent in one image, sheened (under a coat too) and not (so packets hold both),
// through both integrators and samplers: the sheen's lanes are the float instance's bits; --profile
// counts every hit in lane types.
TEST_CASE("glTF sheen: byte for byte the host backend's at W = 1, 4, 8, 16, all shading in lane types" *
          doctest::test_suite("cli")) {
  TempDir dir;
  nlohmann::json ext = sheenExt({0.8, 0.9, 1.0}, 0.35);
  ext["KHR_materials_clearcoat"] = {{"clearcoatFactor", 0.5}, {"clearcoatRoughnessFactor", 0.2}};
  dir.write("sheen.gltf", sheenGltf(0.3f, 0.5f, ext));
  dir.write("sheen.json", sceneText("sheen.gltf", nullptr, {{"type", "metal_rough"}, {"metallic", 0.3}, {"roughness", 0.5}}));
  for (const char* integrator : {"direct", "path"})
    for (const char* sampler : {"sobol", "independent"}) {
      CAPTURE(integrator);
      CAPTURE(sampler);
      const std::vector<std::string> common = {"render", dir.file("sheen.json"), "-q", "--integrator", integrator,
                                               "--sampler", sampler, "--overwrite"};
      checkLanesMatchHost(common, dir, {"1", "4", "8", "16"});
    }
  CliResult r = runMontecl({"render", dir.file("sheen.json"), "--profile", "-q", "-o", dir.file("p.pfm"), "--overwrite"});
  REQUIRE(r.exitCode == 0);
  INFO(r.out);
  CHECK(r.out.find("\nshading: 100.0% of") != std::string::npos);
}

}  // namespace test_file_gltf_sheen
