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
#include "kernels/shared/transmission_mix.h"
#include "lanes_vs_host.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "test_images.h"
#include "util/errors.h"

namespace test_file_gltf_transmission {  // keeps this file's helpers apart in a unity batch

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

// Independent samples unless told otherwise: the z-tests take their error from var/n.
Film renderFile(const std::string& path, std::uint32_t seed = 0, Sampler sampler = Sampler::Independent) {
  std::vector<std::string> warnings;
  Scene s = loadScene(path, warnings);
  s.render.seed = seed;
  s.render.sampler = sampler;
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

// The partly transmissive case: factor kMixT on a grey tent of metallic kMixMetallic, so
// p = t (1 - metallic) = 0.3. Writes mix.json (mixSpp samples) and the two kinds it splits into,
// glass.json and rest.json (256 samples), into dir.
const float kMixT = 0.5f, kMixMetallic = 0.4f;
void writeMixtureScenes(TempDir& dir, int mixSpp) {
  const float p = kMixT * (1.0f - kMixMetallic);
  // A grey base colour: the metal_rough part reflects about half, the glass passes nearly all.
  dir.write("plain.gltf", tentGltf(0.0f, 0.3f, nullptr, 0.5f));
  dir.write("mix.gltf", tentGltf(kMixMetallic, 0.3f, {{"KHR_materials_transmission", {{"transmissionFactor", kMixT}}},
                                                       {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}, 0.5f));
  dir.write("mix.json", sceneText("mix.gltf", nullptr, mixSpp));
  // The glass the mixture picks is tinted by the base colour: the factor-1 material's.
  dir.write("glass.gltf", tentGltf(0.0f, 0.3f, {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                                 {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}, 0.5f));
  dir.write("glass.json", sceneText("glass.gltf", nullptr, 256));
  dir.write("rest.json", sceneText("plain.gltf", {{"type", "metal_rough"}, {"metallic", kMixMetallic / (1.0f - p)}, {"roughness", 0.3}}, 256));
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

// glTF's default factors (1, 1) are a rough metal, and a metal transmits nothing (glTF's BSDF is
// metallic x metal + (1 - metallic) x the dielectric that transmits): transmission on them renders
// the metal itself, bit for bit. The (0, 1) pair, which the loader draws as Lambert, counts as
// metallic 0: a tiny factor stays close to that material, and factor 1 is the thin sheet.
TEST_CASE("glTF transmission on the default factors (1, 1): the rough metal, which transmits nothing" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  auto transmissive = [](float t) { return nlohmann::json{{"KHR_materials_transmission", {{"transmissionFactor", t}}}}; };
  dir.write("metal.gltf", tentGltf(1.0f, 1.0f, nullptr));
  dir.write("full.gltf", tentGltf(1.0f, 1.0f, transmissive(1.0f)));
  dir.write("tiny.gltf", tentGltf(0.0f, 1.0f, transmissive(1e-6f)));
  dir.write("sheet.gltf", tentGltf(0.0f, 1.0f, transmissive(1.0f)));
  std::vector<std::string> warnings;
  for (const char* name : {"metal", "full", "tiny", "sheet"})
    dir.write(std::string(name) + ".json", sceneText(std::string(name) + ".gltf", nullptr, 8));
  const Scene metal = loadScene(dir.file("metal.json"), warnings), full = loadScene(dir.file("full.json"), warnings);
  CHECK(metal.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(metal.materials[0].metallic == 1.0f);
  CHECK(full.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(full.materials[0].metallic == 1.0f);
  CHECK(sameFilm(renderFile(dir.file("metal.json")), renderFile(dir.file("full.json"))));
  const Scene tiny = loadScene(dir.file("tiny.json"), warnings);
  CHECK(tiny.materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(tiny.materials[0].metallic == 0.0f);
  CHECK(loadScene(dir.file("sheet.json"), warnings).materials[0].kind == MCL_MATERIAL_thin_dielectric);
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
  const float t = kMixT, metallic = kMixMetallic, p = t * (1.0f - metallic);
  writeMixtureScenes(dir, 256);
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

// The pick's number: under sobol a pixel's own set per bounce, whatever the hit (so shade_direct,
// shade_direct_hit and record_aov rebuild the same kind), its N samples choosing the glass within the
// sub-sequence count K of p N (each of the K scrambled sub-sequences has one point in each of its
// N/K intervals); under independent the hash of the hit, as before the sampler existed.
TEST_CASE("glTF transmission: under sobol a pixel's picks of the glass are stratified; independent hashes the hit" * doctest::test_suite("cpu")) {
  Material m{};
  m.alpha.w = as_float((uint)MCL_MATERIAL_metal_rough);
  const float t = 0.5f, metallic = 0.4f, p = t * (1.0f - metallic);
  m.params0 = make_float4(metallic, 0.3f, 0.0f, 0.0f);
  m.params1 = make_float4(t, 1.5f, 1.0f, 0.0f);
  FrameParams f{};
  f.seed = 7u;
  const uint n = 64, k = 4;
  f.sobolSplits = k;
  uint64_t rng = 12345u;
  auto next = [&rng] {  // a different hit and direction for every call
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return float((rng >> 40) & 0xffffffu) / 16777216.0f;
  };
  auto glass = [](const Material& r) { return as_uint(r.alpha.w) == (uint)MCL_MATERIAL_dielectric; };
  const int lo = int(k * std::floor(p * n / k)), hi = int(k * std::ceil(p * n / k));
  int strayPixels = 0;
  for (uint bounce : {0u, 3u})
    for (uint pixel = 0; pixel < 64; ++pixel) {
      int picks = 0;
      for (uint s = 0; s < n; ++s) {
        Hit h{next(), pixel, next(), next()};
        const float3 dir = make_float3(next() - 0.5f, next() - 0.5f, 1.0f);
        f.sampler = MCL_SAMPLER_SOBOL;
        const Material r = hit_transmission(&f, m, sample_ref(pixel, s, bounce), h, dir);
        picks += glass(r);
        // Another hit of the same sample and bounce: the same kind.
        Hit other{next(), pixel + 1u, next(), next()};
        REQUIRE(glass(hit_transmission(&f, m, sample_ref(pixel, s, bounce), other, dir)) == glass(r));
        f.sampler = MCL_SAMPLER_INDEPENDENT;
        REQUIRE(glass(hit_transmission(&f, m, sample_ref(pixel, s, bounce), h, dir)) == (hit_uniform(h, dir) < p));
      }
      strayPixels += picks < lo || picks > hi;
    }
  CAPTURE(lo);
  CAPTURE(hi);
  // Binomial picks (the hash of the hit, under either sampler before) land outside [lo, hi] for
  // about half the pixels.
  CHECK(strayPixels == 0);
}

// Unbiased under sobol too: the mixture's image mean, averaged over 16 seeds, is the mixture of the
// two kinds' (rendered with independent samples), within 4 standard errors of the seeds' spread.
TEST_CASE("glTF transmission between 0 and 1 under sobol: the mixture over 16 seeds" * doctest::test_suite("cpu")) {
  TempDir dir;
  const float t = kMixT, metallic = kMixMetallic, p = t * (1.0f - metallic);
  writeMixtureScenes(dir, 16);
  const Film glass = renderFile(dir.file("glass.json"), 2), rest = renderFile(dir.file("rest.json"), 3);
  const int seeds = 16;
  double sum[3] = {0, 0, 0}, sumSq[3] = {0, 0, 0};
  for (int seed = 0; seed < seeds; ++seed) {
    const Film mix = renderFile(dir.file("mix.json"), std::uint32_t(100 + seed), Sampler::Sobol);
    for (int c = 0; c < 3; ++c) {
      const double v = imageMean(mix, c);
      sum[c] += v;
      sumSq[c] += v * v;
    }
  }
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const double mean = sum[c] / seeds, var = (sumSq[c] - seeds * mean * mean) / (seeds - 1);
    const ImageEstimate g = imageEstimate(glass, c), r = imageEstimate(rest, c);
    const double expect = p * g.mean + (1.0 - p) * r.mean;
    const double se = std::sqrt(var / seeds + p * p * g.standardError * g.standardError +
                                (1 - p) * (1 - p) * r.standardError * r.standardError);
    CAPTURE(mean);
    CAPTURE(expect);
    CHECK(std::fabs(mean - expect) / se < 4.0);
    const double wrongExpect = t * g.mean + (1.0 - t) * r.mean;  // glass picked with probability t
    CHECK(std::fabs(mean - wrongExpect) / se > 4.0);
  }
}

// Glass whose metallicRoughnessTexture says smooth (G 0) renders smooth whatever roughnessFactor
// (1, the default) says: the texture makes the per-hit choice of transmission_mix.h, whose glass
// takes the roughness after the texture: the scene file's smooth dielectric, bit for bit, and not
// the factor's rough one.
TEST_CASE("glTF transmission: the glass's roughness comes from the metallicRoughnessTexture's G" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("smooth.png"), 4, 4, 3, [](int, int, int) { return 0; });  // G 0, B 0
  nlohmann::json g = nlohmann::json::parse(tentGltf(0.0f, 1.0f, {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                                                   {"KHR_materials_volume", {{"thicknessFactor", 0.1}}}}));
  g["images"] = {{{"uri", "smooth.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}};
  dir.write("textured.gltf", g.dump());
  dir.write("plain.gltf", tentGltf(0.0f, 0.5f, nullptr));
  dir.write("textured.json", sceneText("textured.gltf", nullptr, 8));
  dir.write("smooth.json", sceneText("plain.gltf", {{"type", "dielectric"}, {"ior", 1.5}}, 8));
  dir.write("rough.json", sceneText("plain.gltf", {{"type", "dielectric"}, {"ior", 1.5}, {"roughness", 1.0}}, 8));
  const Film textured = renderFile(dir.file("textured.json"));
  CHECK(sameFilm(textured, renderFile(dir.file("smooth.json"))));
  CHECK_FALSE(sameFilm(textured, renderFile(dir.file("rough.json"))));
}

// The packet stages read the metallic-roughness texture in lanes and make the transmission's
// per-sample kind pick in lanes (stages/stage_lanes.h lane_frame): byte for byte the host's, for
// a solid and a thin mixture whose metallic and roughness vary texel by texel, both samplers
// (sobol picks by the sample's dimension, independent by a hash of the hit).
TEST_CASE("glTF transmission with a metallicRoughnessTexture: byte for byte the host backend's at W = 1, 4, 8, 16" *
          doctest::test_suite("cli")) {
  TempDir dir;
  writeImage8(dir.file("mr.png"), 8, 8, 3, [](int x, int y, int c) { return c == 0 ? 0 : (37 * x + 91 * y * c) % 256; });
  for (const bool solid : {true, false}) {
    nlohmann::json ext = {{"KHR_materials_transmission", {{"transmissionFactor", 0.6}}}};
    if (solid) ext["KHR_materials_volume"] = {{"thicknessFactor", 0.1}};
    nlohmann::json g = nlohmann::json::parse(tentGltf(0.5f, 0.8f, ext));
    g["images"] = {{{"uri", "mr.png"}}};
    g["textures"] = {{{"source", 0}}};
    g["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0}};
    dir.write("mix.gltf", g.dump());
    dir.write("mix.json", sceneText("mix.gltf", nullptr, 4));
    for (const char* integrator : {"direct", "path"})
      for (const char* sampler : {"sobol", "independent"}) {
        CAPTURE(solid);
        CAPTURE(integrator);
        CAPTURE(sampler);
        const std::vector<std::string> common = {"render", dir.file("mix.json"), "-q", "--integrator", integrator,
                                                 "--sampler", sampler, "--overwrite"};
        checkLanesMatchHost(common, dir, {"1", "4", "8", "16"});
      }
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

}  // namespace test_file_gltf_transmission
