// test_gltf_transmission.cpp: glTF KHR_materials_transmission (+ _ior, _volume) onto the material
// kinds (host/scene/gltf_transmission.cpp, kernels/shared/transmission_mix.h): factor 1 renders
// bit-identically to the scene file's thin_dielectric (no volume) and dielectric (a volume), a
// factor of 0 to the plain metal_rough; a partial factor renders as the mixture of the two kinds
// (z-tests of the image means); bad values are one InputError line naming the key.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "util/errors.h"

using namespace montecl;
using namespace montecl_test;

namespace {

// The tent mesh as glTF, base colour `base` (white), the given factors and material extensions.
std::string tentGltf(float metallic, float roughness, const nlohmann::json& extensions, float base = 1.0f) {
  nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), base, ""));
  auto& m = g["materials"][0];
  m["pbrMetallicRoughness"]["metallicFactor"] = metallic;
  m["pbrMetallicRoughness"]["roughnessFactor"] = roughness;
  if (!extensions.is_null()) {
    m["extensions"] = extensions;
    for (auto it = extensions.begin(); it != extensions.end(); ++it) g["extensionsUsed"].push_back(it.key());
  }
  return g.dump();
}

// A scene file around mesh `gltf` (with an optional material override) under a constant
// environment and a directional light from above, path traced, seen from above (the tent fills
// the image: glass passes the light down and away, metal_rough sends some of it up).
std::string sceneText(const std::string& gltf, const nlohmann::json& material, int spp) {
  nlohmann::json s = {{"camera", {{"position", {1.2, 3.5, -1}}, {"target", {1.2, 0, -1}}, {"up", {0, 0, -1}},
                                  {"fov_y", 45}, {"width", 12}, {"height", 10}}},
                      {"meshes", {{{"file", gltf}}}},
                      {"environment", {{"radiance", {0.3, 0.2, 0.1}}}},
                      {"lights", {{{"type", "directional"}, {"direction", {0.3, -1, 0.2}}, {"irradiance", {2, 2, 2}}}}},
                      {"render", {{"integrator", "path"}, {"spp", spp}, {"max_depth", 6}}}};
  if (!material.is_null()) s["meshes"][0]["material"] = material;
  return s.dump();
}

Film renderFile(const std::string& path, std::uint32_t seed = 0) {
  std::vector<std::string> warnings;
  Scene s = loadScene(path, warnings);
  s.render.seed = seed;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(hostDeviceInfo(), {});
  RenderStats stats;
  return r.render(s, bvh, stats);
}

bool sameFilm(const Film& a, const Film& b) {
  return a.mean.size() == b.mean.size() && !a.mean.empty() &&
         std::memcmp(a.mean.data(), b.mean.data(), a.mean.size() * sizeof a.mean[0]) == 0 &&
         std::memcmp(a.meanLo.data(), b.meanLo.data(), a.meanLo.size() * sizeof a.meanLo[0]) == 0;
}

std::string loadError(const std::string& path) {
  std::vector<std::string> warnings;
  try {
    loadScene(path, warnings);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("glTF transmission 1: the thin_dielectric and dielectric kinds, bit for bit" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("plain.gltf", tentGltf(0.0f, 0.5f, nullptr));
  dir.write("thin.gltf", tentGltf(0.0f, 0.0f, {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                                {"KHR_materials_ior", {{"ior", 1.5}}}}));
  dir.write("solid.gltf", tentGltf(0.0f, 0.5f, {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                                 {"KHR_materials_ior", {{"ior", 1.33}}},
                                                 {"KHR_materials_volume", {{"thicknessFactor", 0.1}}}}));
  dir.write("thin.json", sceneText("thin.gltf", nullptr, 8));
  dir.write("solid.json", sceneText("solid.gltf", nullptr, 8));
  dir.write("thin-ref.json", sceneText("plain.gltf", {{"type", "thin_dielectric"}, {"ior", 1.5}}, 8));
  dir.write("solid-ref.json", sceneText("plain.gltf", {{"type", "dielectric"}, {"ior", 1.33}, {"roughness", 0.5}}, 8));
  dir.write("plain.json", sceneText("plain.gltf", nullptr, 8));
  std::vector<std::string> warnings;
  CHECK(loadScene(dir.file("thin.json"), warnings).materials[0].kind == MCL_MATERIAL_thin_dielectric);
  CHECK(loadScene(dir.file("solid.json"), warnings).materials[0].kind == MCL_MATERIAL_dielectric);
  for (const std::string& w : warnings) CHECK(w.find("KHR_materials") == std::string::npos);  // read, not ignored
  const Film thin = renderFile(dir.file("thin.json")), solid = renderFile(dir.file("solid.json"));
  CHECK(sameFilm(thin, renderFile(dir.file("thin-ref.json"))));
  CHECK(sameFilm(solid, renderFile(dir.file("solid-ref.json"))));
  CHECK_FALSE(sameFilm(thin, solid));
  CHECK_FALSE(sameFilm(thin, renderFile(dir.file("plain.json"))));
}

TEST_CASE("glTF transmission 0: the plain metal_rough, bit for bit" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("plain.gltf", tentGltf(0.3f, 0.4f, nullptr));
  dir.write("zero.gltf", tentGltf(0.3f, 0.4f, {{"KHR_materials_transmission", {{"transmissionFactor", 0.0}}},
                                                {"KHR_materials_ior", {{"ior", 1.5}}}}));
  dir.write("plain.json", sceneText("plain.gltf", nullptr, 8));
  dir.write("zero.json", sceneText("zero.gltf", nullptr, 8));
  CHECK(sameFilm(renderFile(dir.file("plain.json")), renderFile(dir.file("zero.json"))));
}

// glTF's partly transmissive BSDF is p x dielectric + (1 - p) x metal_rough(metallic / (1 - p)),
// p = t (1 - metallic): the image means agree with the same mixture of the two renders.
TEST_CASE("glTF transmission between 0 and 1: the mixture of the two kinds" * doctest::test_suite("cpu")) {
  TempDir dir;
  const float t = 0.5f, metallic = 0.4f, p = t * (1.0f - metallic);
  // A grey base colour: the metal_rough part reflects about half, the glass passes nearly all.
  dir.write("plain.gltf", tentGltf(0.0f, 0.3f, nullptr, 0.5f));
  dir.write("mix.gltf", tentGltf(metallic, 0.3f, {{"KHR_materials_transmission", {{"transmissionFactor", t}}},
                                                   {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}, 0.5f));
  dir.write("mix.json", sceneText("mix.gltf", nullptr, 256));
  dir.write("glass.json", sceneText("plain.gltf", {{"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.3}}, 256));
  dir.write("rest.json", sceneText("plain.gltf", {{"type", "metal_rough"}, {"metallic", metallic / (1.0f - p)}, {"roughness", 0.3}}, 256));
  const Film mix = renderFile(dir.file("mix.json"), 1), glass = renderFile(dir.file("glass.json"), 2);
  const Film rest = renderFile(dir.file("rest.json"), 3);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const ImageEstimate m = imageEstimate(mix, c), g = imageEstimate(glass, c), r = imageEstimate(rest, c);
    const double expect = p * g.mean + (1.0 - p) * r.mean;
    const double se = std::sqrt(m.standardError * m.standardError + p * p * g.standardError * g.standardError +
                                (1 - p) * (1 - p) * r.standardError * r.standardError);
    CHECK(std::fabs(m.mean - expect) / se < 4.0);
    // The test can tell: glass picked with probability t (metallic ignored) is measurably wrong.
    const double wrongExpect = t * g.mean + (1.0 - t) * r.mean;
    CHECK(std::fabs(m.mean - wrongExpect) / se > 4.0);
  }
}

TEST_CASE("glTF transmission: bad values are one line naming the key" * doctest::test_suite("cpu")) {
  TempDir dir;
  struct Bad {
    nlohmann::json ext;
    const char* key;
  };
  const Bad bad[] = {
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}, "KHR_materials_transmission.transmissionFactor: must be in [0, 1]"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", -0.1}}}}, "transmissionFactor: must be in [0, 1]"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", "1"}}}}, "transmissionFactor: must be a number"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1}}}, {"KHR_materials_ior", {{"ior", 0.5}}}}, "KHR_materials_ior.ior: must be >= 1 (or 0)"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1}}}, {"KHR_materials_ior", {{"ior", -1.5}}}}, "ior: must be >= 1 (or 0)"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1}}}, {"KHR_materials_volume", {{"thicknessFactor", -1}}}}, "thicknessFactor: must be >= 0"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.ext.dump());
    dir.write("bad.gltf", tentGltf(0.0f, 0.0f, b.ext));
    const std::string e = loadError(dir.file("bad.gltf"));
    CHECK(e.find("materials[0].extensions.") != std::string::npos);
    CHECK(e.find(b.key) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
  }
  // ior 0 is the extension's specular-glossiness mode: valid, not modelled (a warning).
  dir.write("zero.gltf", tentGltf(0.0f, 0.0f, {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                                                {"KHR_materials_ior", {{"ior", 0}}}}));
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("zero.gltf"), warnings);
  CHECK(s.materials[0].ior == 1.5f);
  bool warned = false;
  for (const std::string& w : warnings) warned = warned || w.find("ior 0") != std::string::npos;
  CHECK(warned);
}
