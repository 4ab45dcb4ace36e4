// test_gltf_clearcoat.cpp: glTF KHR_materials_clearcoat onto metal_rough's coat
// (host/scene/gltf_clearcoat.cpp, kernels/shared/bsdf_metal_rough.h): the file's coat renders
// bit-identically to the scene file's clearcoat keys, factor 0 to the uncoated material; a file
// that requires the extension loads; what is not modelled is warned; bad values are one line
// naming the key; a smooth coat over a smooth black base under a white sky renders its closed
// form (z-test of the image mean); the packet stages shade coated and uncoated hits in one packet byte for byte as
// the host backend does at W = 1, 4, 8, 16, all in lane types.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "film_stats.h"
#include "lanes_vs_host.h"
#include "gltf_extension_scenes.h"
#include "mesh_files.h"
#include "scene_renders.h"
#include "util/errors.h"

namespace test_file_gltf_clearcoat {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// The tent mesh as glTF (a red base of the given factors) with the material extensions `ext`.
std::string coatGltf(float metallic, float roughness, const nlohmann::json& ext) {
  return tentGltf(nlohmann::json::array({0.8, 0.1, 0.05, 1.0}), metallic, roughness, ext);
}

nlohmann::json coatExt(double factor, double roughness) {
  return {{"KHR_materials_clearcoat", {{"clearcoatFactor", factor}, {"clearcoatRoughnessFactor", roughness}}}};
}

// The scene looking at the tent (gltf_extension_scenes.h).
std::string sceneText(const std::string& gltf, const nlohmann::json& material, const nlohmann::json& second = nullptr) {
  return tentSceneText(gltf, material, second);
}

}  // namespace

TEST_CASE("glTF clearcoat: the file's coat is the scene file's clearcoat keys bit for bit; factor 0 is no coat" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("plain.gltf", coatGltf(0.0f, 0.6f, nullptr));
  dir.write("coat.gltf", coatGltf(0.0f, 0.6f, coatExt(0.8, 0.2)));
  dir.write("off.gltf", coatGltf(0.0f, 0.6f, coatExt(0.0, 0.5)));
  dir.write("coat.json", sceneText("coat.gltf", nullptr));
  dir.write("off.json", sceneText("off.gltf", nullptr));
  dir.write("plain.json", sceneText("plain.gltf", nullptr));
  const auto keys = [](double coat, double rough) {
    return nlohmann::json{{"type", "metal_rough"}, {"albedo", {0.8, 0.1, 0.05}}, {"metallic", 0}, {"roughness", 0.6},
                          {"clearcoat", coat}, {"clearcoat_roughness", rough}};
  };
  dir.write("keys.json", sceneText("plain.gltf", keys(0.8, 0.2)));
  dir.write("rougher.json", sceneText("plain.gltf", keys(0.8, 0.3)));
  const Film coat = renderSceneFile(dir.file("coat.json")), plain = renderSceneFile(dir.file("plain.json"));
  CHECK(sameMeanBits(coat, renderSceneFile(dir.file("keys.json"))));
  CHECK_FALSE(sameMeanBits(coat, renderSceneFile(dir.file("rougher.json"))));  // the roughness is read
  CHECK_FALSE(sameMeanBits(coat, plain));                                   // and the coat shows
  CHECK(sameMeanBits(plain, renderSceneFile(dir.file("off.json"))));
}

TEST_CASE("glTF clearcoat: a file requiring it loads; the (0, 1) pair becomes metal_rough; what is left out is warned" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  nlohmann::json ext = coatExt(1.0, 0.1);
  ext["KHR_materials_clearcoat"]["clearcoatTexture"] = {{"index", 0}};
  ext["KHR_materials_clearcoat"]["clearcoatNormalTexture"] = {{"index", 0}};
  nlohmann::json g = nlohmann::json::parse(coatGltf(0.0f, 1.0f, ext));
  g["extensionsRequired"] = {"KHR_materials_clearcoat"};
  dir.write("req.gltf", g.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("req.gltf"), warnings);
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(s.materials[0].roughness == 1.0f);
  CHECK(s.materials[0].clearcoat == 1.0f);
  CHECK(s.materials[0].clearcoatRoughness == 0.1f);
  int textures = 0, normal = 0, ignored = 0;
  for (const std::string& w : warnings) {
    textures += w.find("clearcoatTexture and clearcoatRoughnessTexture not read") != std::string::npos;
    normal += w.find("clearcoatNormalTexture not read") != std::string::npos;
    ignored += w.find("KHR_materials_clearcoat' not used") != std::string::npos;
  }
  CHECK(textures == 1);
  CHECK(normal == 1);
  CHECK(ignored == 0);
}

// A square facing the camera seen head-on through a 4-degree field of view (n.wo > 0.9993, so
// Schlick's term is 0.04 to within 1e-16), a smooth black dielectric base (F0 0.04) under a smooth
// coat of factor c, in a sky of radiance 1 with nothing else: direct lighting (MIS of the sky's
// samples and the BSDF's) sees the one-bounce white furnace, c F + (1 - c F) F = 0.04 c + (1 -
// 0.04 c) 0.04, up to the near-mirror GGX lobes' loss (alpha 1e-3: under 1e-6 at normal incidence).
TEST_CASE("glTF clearcoat: a smooth coat over a black base under a white sky renders c F + (1 - c F) F (z-test)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  for (const double c : {1.0, 0.5}) {
    CAPTURE(c);
    const std::string white = headOnWhiteSkyQuad(dir, coatExt(c, 0.0));
    const ImageEstimate e = imageEstimate(renderSceneFile(white), 1);
    const double want = 0.04 * c + (1.0 - 0.04 * c) * 0.04;
    INFO("image mean " << e.mean << " +- " << e.standardError << ", closed form " << want);
    CHECK(std::fabs(e.mean - want) <= 4.0 * e.standardError + 1e-5);
    CHECK(e.standardError < 0.01 * want);  // and the test is sharp enough to tell c F from F alone
  }
}

TEST_CASE("glTF clearcoat: bad values are one line naming the key" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::pair<nlohmann::json, const char*> bad[] = {
      {coatExt(1.5, 0.0), "KHR_materials_clearcoat.clearcoatFactor: must be a number in [0, 1]"},
      {coatExt(-0.1, 0.0), "clearcoatFactor: must be a number in [0, 1]"},
      {coatExt(1.0, 2.0), "KHR_materials_clearcoat.clearcoatRoughnessFactor: must be a number in [0, 1]"},
      {{{"KHR_materials_clearcoat", {{"clearcoatFactor", "1"}}}}, "clearcoatFactor: must be a number in [0, 1]"},
  };
  for (const auto& b : bad) {
    const std::string what = b.first.dump(), key = b.second;
    CAPTURE(what);
    dir.write("bad.gltf", coatGltf(0.0f, 0.5f, b.first));
    const std::string e = sceneLoadError(dir.file("bad.gltf"));
    CHECK(e.find("bad.gltf: materials[0].extensions.") != std::string::npos);
    CHECK(e.find(key) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
  }
}

// Two copies of the tent in one image, coated and not (so packets hold both), through both
// integrators and samplers: the coat's lanes are the float instance's bits; --profile counts every
// hit in lane types.
TEST_CASE("glTF clearcoat: byte for byte the host backend's at W = 1, 4, 8, 16, all shading in lane types" *
          doctest::test_suite("cli")) {
  TempDir dir;
  dir.write("coat.gltf", coatGltf(0.3f, 0.5f, coatExt(0.9, 0.15)));
  dir.write("coat.json", sceneText("coat.gltf", nullptr, {{"type", "metal_rough"}, {"metallic", 0.3}, {"roughness", 0.5}}));
  for (const char* integrator : {"direct", "path"})
    for (const char* sampler : {"sobol", "independent"}) {
      CAPTURE(integrator);
      CAPTURE(sampler);
      const std::vector<std::string> common = {"render", dir.file("coat.json"), "-q", "--integrator", integrator,
                                               "--sampler", sampler, "--overwrite"};
      checkLanesMatchHost(common, dir, {"1", "4", "8", "16"});
    }
  CliResult r = runMontecl({"render", dir.file("coat.json"), "--profile", "-q", "-o", dir.file("p.pfm"), "--overwrite"});
  REQUIRE(r.exitCode == 0);
  INFO(r.out);
  CHECK(r.out.find("\nshading: 100.0% of") != std::string::npos);
}

}  // namespace test_file_gltf_clearcoat
