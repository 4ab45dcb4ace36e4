// test_gltf_blend.cpp: glTF alphaMode BLEND as stochastic transparency (host/scene/gltf_material.cpp,
// kernels/shared/surface_texture.h alpha_hit_exists): a ray meets a BLEND surface with probability
// alpha = baseColorFactor's alpha x the base colour texture's and passes through otherwise, by a
// hash of the ray and the triangle. Checked against the estimator's own standard error (independent
// sampler, the films' per-pixel M2): an unlit quad of colour c and alpha a (factor only, or factor x
// texture) before a constant environment B shows a c + (1 - a) B; a BLEND occluder seen only by
// shadow rays lets 1 - a of a directional light through; an emitter of alpha a sends a of its light
// by light sampling (its samples weighted by the coverage), BRDF sampling (rays that meet it with
// probability a) and MIS alike. The loader reads factor-only BLEND with no
// warning (and MASK as before), the images are byte for byte the same on the host backend and
// the default OpenCL device at W = 1, 4, 8, 16, and montecl bench's tracers agree ray for ray.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "lanes_vs_host.h"
#include "mesh_files.h"
#include "scene_renders.h"
#include "test_images.h"

namespace test_file_gltf_blend {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;
using nlohmann::json;

namespace {

// A quad (corners in order, UVs (0,0) (1,0) (1,1) (0,1)) as glTF with `material` as its material 0.
std::string quadGltf(const std::vector<float>& corners, const json& material) {
  MeshData m;
  m.positions = corners;
  m.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  m.faces = {{0, 1, 2, 3}};
  json g = json::parse(gltfText(m, 1.0f, ""));
  json lo = {1e30, 1e30, 1e30}, hi = {-1e30, -1e30, -1e30};
  for (std::size_t i = 0; i < corners.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3].get<double>(), double(corners[i]));
    hi[i % 3] = std::max(hi[i % 3].get<double>(), double(corners[i]));
  }
  g["accessors"][0]["min"] = lo;
  g["accessors"][0]["max"] = hi;
  g["materials"][0] = material;
  if (material.contains("extensions"))
    for (auto it = material["extensions"].begin(); it != material["extensions"].end(); ++it)
      g["extensionsUsed"].push_back(it.key());
  return g.dump();
}

// An unlit (KHR_materials_unlit: it shows its base colour, reflects nothing) BLEND material of
// colour c and alpha factor a, with base colour texture 0 when textured.
json unlitBlend(float c, float a, bool textured) {
  json pbr = {{"baseColorFactor", {c, c, c, a}}, {"metallicFactor", 0}, {"roughnessFactor", 1}};
  if (textured) pbr["baseColorTexture"] = {{"index", 0}};
  return {{"pbrMetallicRoughness", pbr}, {"alphaMode", "BLEND"}, {"extensions", {{"KHR_materials_unlit", json::object()}}}};
}

// The mean over every pixel of channel 0 and its standard error: the pixels' means averaged, the
// variance of each pixel's mean M2 / (n (n - 1)) (independent samples) summed over pixels / P^2.
struct Estimate {
  double mean = 0.0, se = 0.0;
};
Estimate pooled(const Film& f) {
  Estimate e;
  const double p = double(f.mean.size());
  double var = 0.0;
  for (std::size_t i = 0; i < f.mean.size(); ++i) {
    const double n = double(f.count[i]);
    e.mean += double(f.mean[i].x) + double(f.meanLo[i].x);
    var += (double(f.m2[i].x) + double(f.m2Lo[i].x)) / (n * (n - 1.0));
  }
  e.mean /= p;
  e.se = std::sqrt(var) / p;
  return e;
}

// A camera 3 in front of a quad at z = -1 that fills its whole view, under a constant environment
// of radiance 1 (what a ray through the quad sees), direct lighting, independent samples.
std::string throughScene(const std::vector<std::string>& gltfs) {
  json meshes = json::array();
  for (const std::string& g : gltfs) meshes.push_back(json{{"file", g}});
  json s = {{"camera", {{"position", {1, 0.75, 2}}, {"target", {1, 0.75, -1}}, {"fov_y", 20}, {"width", 24}, {"height", 24}}},
            {"meshes", meshes},
            {"environment", {{"radiance", {1, 1, 1}}}},
            {"render", {{"integrator", "direct"}, {"spp", 32}, {"sampler", "independent"}, {"seed", 3}}}};
  return s.dump();
}

const std::vector<float> kFacingQuad = {0, 0, -1, 2, 0, -1, 2, 1.5f, -1, 0, 1.5f, -1};

// A white floor (y = 0) seen from straight above (x, z in about [-0.5, 0.5]) lit by a directional
// light travelling along (1, -1, 0); a black BLEND quad of alpha a at y = 1 over x in [-2.5, -0.45]
// lies on every shadow ray of the seen floor (they cross y = 1 at x in [-1.5, -0.5]) but on no camera
// ray (x within 0.4 there). Without the occluder (occluder false) the floor is lit everywhere.
std::string shadowScene(const TempDir& dir, float a, bool occluder) {
  dir.write("floor.gltf", quadGltf({-3, 0, 3, 3, 0, 3, 3, 0, -3, -3, 0, -3},
                                   {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0},
                                                              {"roughnessFactor", 1}}}}));
  dir.write("occluder.gltf", quadGltf({-2.5f, 1, 2, -0.45f, 1, 2, -0.45f, 1, -2, -2.5f, 1, -2},
                                      {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, a}}, {"metallicFactor", 0},
                                                                 {"roughnessFactor", 1}}},
                                       {"alphaMode", "BLEND"}, {"doubleSided", true}}));
  json meshes = json::array({json{{"file", dir.file("floor.gltf")}}});
  if (occluder) meshes.push_back(json{{"file", dir.file("occluder.gltf")}});
  json s = {{"camera", {{"position", {0, 5, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}}, {"fov_y", 10}, {"width", 20}, {"height", 20}}},
            {"meshes", meshes},
            {"lights", {{{"type", "directional"}, {"direction", {1, -1, 0}}, {"irradiance", {2, 2, 2}}}}},
            {"render", {{"integrator", "direct"}, {"spp", 32}, {"sampler", "independent"}, {"seed", 5}}}};
  return s.dump();
}

}  // namespace

TEST_CASE("glTF BLEND: read as stochastic transparency (factor alone or x the texture), no warning; MASK as before" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("a.png"), 2, 2, 4, [](int, int, int c) { return c == 3 ? 128 : 200; });
  json g = json::parse(quadGltf(kFacingQuad, unlitBlend(0.2f, 0.3f, false)));
  g["images"] = json::array({json{{"uri", "a.png"}}});
  g["textures"] = json::array({json{{"source", 0}}});
  json textured = unlitBlend(0.2f, 0.6f, true);
  json opaque = {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}}, {"alphaMode", "BLEND"}};
  json mask = {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.5}}}}, {"alphaMode", "MASK"}};
  json bad = {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1.5}}}}, {"alphaMode", "BLEND"}};
  g["materials"] = json::array({g["materials"][0], textured, opaque, mask});
  auto prim = g["meshes"][0]["primitives"][0];
  g["meshes"][0]["primitives"] = json::array();
  for (int k = 0; k < 4; ++k) {
    prim["material"] = k;
    g["meshes"][0]["primitives"].push_back(prim);
  }
  dir.write("m.gltf", g.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("m.gltf"), warnings);
  REQUIRE(s.triangles.size() == 8);
  INFO(warnings.size());
  for (const std::string& w : warnings) CHECK(w.find("BLEND") == std::string::npos);
  const MaterialDesc& factor = s.materials[s.triangles[0].material];
  CHECK(factor.alphaBlend);
  CHECK(factor.alphaFactor == 0.3f);
  CHECK(factor.alphaTexture.empty());
  const MaterialDesc& tex = s.materials[s.triangles[2].material];
  CHECK(tex.alphaBlend);
  CHECK(tex.alphaFactor == 0.6f);
  CHECK(tex.alphaTexture == tex.emissionTexture);  // unlit: the base colour texture emits and is the alpha
  CHECK(!tex.alphaTexture.empty());
  const MaterialDesc& one = s.materials[s.triangles[4].material];
  CHECK(one.alphaBlend);
  CHECK(one.alphaFactor == 1.0f);
  const MaterialDesc& m = s.materials[s.triangles[6].material];
  CHECK(!m.alphaBlend);
  CHECK(m.alphaCutoff == 0.5f);
  // A scene file's alpha_cutoff on the mesh makes cut-outs of its BLEND materials.
  dir.write("cut.json", json{{"camera", "auto"}, {"meshes", {{{"file", dir.file("m.gltf")}, {"material", {{"alpha_cutoff", 0.4}}}}}}}.dump());
  const Scene cut = loadScene(dir.file("cut.json"), warnings);
  REQUIRE(cut.triangles.size() == 8);
  CHECK(!cut.materials[cut.triangles[0].material].alphaBlend);
  CHECK(cut.materials[cut.triangles[0].material].alphaCutoff == 0.4f);
  // A base colour alpha outside [0, 1]: an error naming the material.
  g["materials"][2] = bad;
  dir.write("m.gltf", g.dump());
  CHECK_THROWS(loadScene(dir.file("m.gltf"), warnings));
}

TEST_CASE("glTF BLEND: a quad of alpha a before the environment shows a c + (1 - a) B (factor, factor x texture, two layers)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  // The texture's alpha 128 / 255 everywhere (its colour 255: the unlit quad shows c x 1).
  writeImage8(dir.file("a.png"), 2, 2, 4, [](int, int, int c) { return c == 3 ? 128 : 255; });
  const float c = 0.2f;
  struct Row {
    float factor;
    bool textured;
  };
  for (const Row row : {Row{0.3f, false}, Row{0.7f, false}, Row{0.8f, true}}) {
    CAPTURE(row.factor);
    CAPTURE(row.textured);
    json g = json::parse(quadGltf(kFacingQuad, unlitBlend(c, row.factor, row.textured)));
    if (row.textured) {
      g["images"] = json::array({json{{"uri", "a.png"}}});
      g["textures"] = json::array({json{{"source", 0}}});
    }
    dir.write("quad.gltf", g.dump());
    dir.write("scene.json", throughScene({dir.file("quad.gltf")}));
    const Film f = renderSceneFile(dir.file("scene.json"));
    REQUIRE(f.mean.size() == 24u * 24u);
    const double a = double(row.factor) * (row.textured ? 128.0 / 255.0 : 1.0);
    const double expected = a * c + (1.0 - a) * 1.0;
    const Estimate e = pooled(f);
    // The samples are c or 1: the standard error as the binomial's, and the film's agree.
    const double n = double(f.mean.size()) * 32.0;
    CHECK(e.se == doctest::Approx(std::sqrt(a * (1.0 - a) / n) * (1.0 - c)).epsilon(0.1));
    const double z = (e.mean - expected) / e.se;
    CAPTURE(e.mean);
    CAPTURE(expected);
    CAPTURE(e.se);
    CHECK(std::fabs(z) < 4.0);
  }
  // Two layers, a1 then a2 behind it: each surface tosses its own coin (the hash holds the
  // triangle), so a1 c1 + (1 - a1) a2 c2 + (1 - a1)(1 - a2) B; one coin for both would give
  // a1 c1 + (a2 - a1) c2 + (1 - a2) B, 0.06 more here (23.5 SE).
  const float a1 = 0.3f, c1 = 0.2f, a2 = 0.5f, c2 = 0.6f;
  dir.write("front.gltf", quadGltf(kFacingQuad, unlitBlend(c1, a1, false)));
  dir.write("back.gltf", quadGltf({0, 0, -1.5f, 2, 0, -1.5f, 2, 1.5f, -1.5f, 0, 1.5f, -1.5f}, unlitBlend(c2, a2, false)));
  dir.write("two.json", throughScene({dir.file("front.gltf"), dir.file("back.gltf")}));
  const Estimate e = pooled(renderSceneFile(dir.file("two.json")));
  const double expected = a1 * c1 + (1.0 - a1) * a2 * c2 + (1.0 - a1) * (1.0 - a2);
  CAPTURE(e.mean);
  CAPTURE(expected);
  CAPTURE(e.se);
  CHECK(std::fabs((e.mean - expected) / e.se) < 4.0);
}

TEST_CASE("glTF BLEND: an occluder of alpha a lets 1 - a of a light through to the shadow it casts" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  for (float a : {0.25f, 0.6f}) {
    CAPTURE(a);
    dir.write("lit.json", shadowScene(dir, a, false));
    dir.write("shadowed.json", shadowScene(dir, a, true));
    const Film lit = renderSceneFile(dir.file("lit.json"));
    const Film shadowed = renderSceneFile(dir.file("shadowed.json"));
    const Estimate l = pooled(lit), s = pooled(shadowed);
    REQUIRE(l.mean > 0.1);
    CHECK(l.se < 1e-6 * l.mean);  // a delta light on a flat white floor: every sample the same
    const double z = (s.mean - (1.0 - a) * l.mean) / s.se;
    CAPTURE(l.mean);
    CAPTURE(s.mean);
    CAPTURE(s.se);
    CHECK(s.se > 0.0);
    CHECK(std::fabs(z) < 4.0);
  }
}

// A white floor seen from y = 0.5 straight down, lit only by an emitting quad of alpha a facing
// down from y = 1 (camera rays never reach it); opaque: the same quad without BLEND.
std::string emitterScene(const TempDir& dir, float a, bool opaque, const char* sampling) {
  dir.write("floor.gltf", quadGltf({-3, 0, 3, 3, 0, 3, 3, 0, -3, -3, 0, -3},
                                   {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1}}, {"metallicFactor", 0},
                                                              {"roughnessFactor", 1}}}}));
  json lamp = {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, a}}, {"metallicFactor", 0}, {"roughnessFactor", 1}}},
               {"emissiveFactor", {1, 1, 1}},
               {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}};
  if (!opaque) lamp["alphaMode"] = "BLEND";
  dir.write("lamp.gltf", quadGltf({-0.5f, 1, -0.5f, 0.5f, 1, -0.5f, 0.5f, 1, 0.5f, -0.5f, 1, 0.5f}, lamp));
  json s = {{"camera", {{"position", {0, 0.5, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}}, {"fov_y", 60}, {"width", 16}, {"height", 16}}},
            {"meshes", {{{"file", dir.file("floor.gltf")}}, {{"file", dir.file("lamp.gltf")}}}},
            {"render", {{"integrator", "direct"}, {"direct_sampling", sampling}, {"spp", 64}, {"sampler", "independent"}, {"seed", 9}}}};
  return s.dump();
}

TEST_CASE("glTF BLEND: an emitter of alpha a sends a of its light, by light, BRDF and MIS sampling alike" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  const float a = 0.35f;
  dir.write("opaque.json", emitterScene(dir, a, true, "light"));
  const Estimate full = pooled(renderSceneFile(dir.file("opaque.json")));
  REQUIRE(full.mean > 0.05);
  for (const std::string sampling : {"light", "brdf", "mis"}) {
    CAPTURE(sampling);
    dir.write("blend.json", emitterScene(dir, a, false, sampling.c_str()));
    const Estimate e = pooled(renderSceneFile(dir.file("blend.json")));
    const double expected = double(a) * full.mean, se = std::sqrt(e.se * e.se + double(a) * double(a) * full.se * full.se);
    CAPTURE(e.mean);
    CAPTURE(expected);
    CAPTURE(se);
    CHECK(se > 0.0);
    CHECK(std::fabs((e.mean - expected) / se) < 4.0);
    // Light sampling weights each sample by the coverage: a times the opaque lamp's samples.
    if (sampling == "light") CHECK(e.mean == doctest::Approx(expected).epsilon(1e-5));
  }
}

TEST_CASE("glTF BLEND: byte for byte the host backend's on the OpenCL device at W = 1, 4, 8, 16" *
          doctest::test_suite("cli")) {
  TempDir dir;
  writeImage8(dir.file("a.png"), 4, 4, 4, [](int x, int y, int c) { return c == 3 ? 40 + 50 * x + 5 * y : 255; });
  // A lit (not unlit) textured BLEND quad over the floor, path traced: camera, bounce and shadow rays
  // meet it; the shadow scene (the occluder factor-only), direct lighting; a BLEND emitter, path traced.
  json quad = json::parse(quadGltf({-0.8f, 0.3f, 0.6f, 0.8f, 0.3f, 0.6f, 0.8f, 1.2f, -0.4f, -0.8f, 1.2f, -0.4f},
                                   {{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.5, 0.3, 0.8}},
                                                              {"baseColorTexture", {{"index", 0}}}}},
                                    {"alphaMode", "BLEND"}, {"doubleSided", true}}));
  quad["images"] = json::array({json{{"uri", "a.png"}}});
  quad["textures"] = json::array({json{{"source", 0}}});
  dir.write("quad.gltf", quad.dump());
  json s = json::parse(shadowScene(dir, 0.5f, true));
  s["meshes"].push_back(json{{"file", dir.file("quad.gltf")}});
  s["camera"] = {{"position", {0.3, 2.5, 3}}, {"target", {0, 0.3, 0}}, {"fov_y", 50}};
  s["environment"] = {{"radiance", {0.3, 0.4, 0.5}}};
  dir.write("path.json", s.dump());
  dir.write("shadow.json", shadowScene(dir, 0.5f, true));
  dir.write("lamp.json", emitterScene(dir, 0.4f, false, "mis"));  // a BLEND emitter: light samples weighted
  for (const std::string scene : {"path.json", "shadow.json", "lamp.json"}) {
    CAPTURE(scene);
    const std::vector<std::string> common = {"render", dir.file(scene), "-q", "--width", "27", "--height", "21",
                                             "--spp", "4", "--integrator", scene == "shadow.json" ? "direct" : "path",
                                             "--overwrite"};
    checkLanesMatchHost(common, dir, {"1", "4", "8", "16"});
  }
}

TEST_CASE("glTF BLEND: montecl bench's tracers (device, host reference, Embree) take the same coin" *
          doctest::test_suite("cli")) {
  TempDir dir;
  // The shadow scene seen from the side: camera and AO rays cross the occluder (alpha 0.5, factor
  // alone) and the floor behind it.
  json s = json::parse(shadowScene(dir, 0.5f, true));
  s["camera"] = {{"position", {-1.5, 3, 3}}, {"target", {-1.2, 0.5, 0}}, {"fov_y", 60}};
  dir.write("bench.json", s.dump());
  CliResult r = runMontecl({"bench", dir.file("bench.json"), "--width", "32", "--height", "24", "--repeat", "1",
                            "--json", dir.file("out.json"), "-q"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const json j = json::parse(readAll(dir.file("out.json")));
  CHECK(j["alpha_tested_triangles"].get<std::size_t>() == 2);  // the occluder's
  for (const auto& k : j["rays"]) {
    INFO("ray kind " << k["kind"]);
    CHECK(k["mismatches"].get<std::size_t>() == 0);
    if (k.contains("embree_mismatches")) CHECK(k["embree_mismatches"].get<std::size_t>() == 0);
  }
  CHECK(j["mismatches_total"].get<std::size_t>() == 0);
}

}  // namespace test_file_gltf_blend
