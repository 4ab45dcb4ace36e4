// test_gltf_transmission_tint.cpp: glTF glass's colour and its transmissionTexture
// (kernels/shared/transmission_tint.h, surface_texture.h hit_transmission_texture): the base colour
// tints the light a transmissive glTF material passes (KHR_materials_transmission's BTDF x
// baseColor) and not the light it reflects: closed forms for a thin sheet and a solid slab under a
// constant sky (z-tests against the film's own standard error), the per-hit kind pick's glass
// tinted too; the transmission factor x the texture's R per hit (a closed form over a lamp); the
// packet stages byte for byte the host backend's.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "lanes_vs_host.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "test_images.h"
#include "util/errors.h"

namespace test_file_gltf_transmission_tint {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

const float kTint[3] = {0.8f, 0.45f, 0.15f};

// A 2 x 1 x 2 box ([0, 2] x [0, 1] x [-2, 0], wound outward: a closed solid), or its top face alone.
MeshData slabMesh(bool closed) {
  MeshData m;
  m.positions = {0, 0, 0, 2, 0, 0, 2, 0, -2, 0, 0, -2, 0, 1, 0, 2, 1, 0, 2, 1, -2, 0, 1, -2};
  m.faces = {{4, 5, 6, 7}};
  if (closed) m.faces.insert(m.faces.end(), {{0, 3, 2, 1}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}});
  return m;
}

// glTF text of mesh m whose one material is base colour `base` with the given factors and
// material extensions.
std::string gltfWith(const MeshData& m, const float base[3], float metallic, float roughness,
                     const nlohmann::json& extensions) {
  nlohmann::json g = nlohmann::json::parse(gltfText(m, 1.0f, ""));
  auto& pbr = g["materials"][0]["pbrMetallicRoughness"];
  pbr["baseColorFactor"] = {base[0], base[1], base[2], 1.0f};
  pbr["metallicFactor"] = metallic;
  pbr["roughnessFactor"] = roughness;
  g["materials"][0]["extensions"] = extensions;
  for (auto it = extensions.begin(); it != extensions.end(); ++it) g["extensionsUsed"].push_back(it.key());
  return g.dump();
}

nlohmann::json transmission(double t, bool solid) {
  nlohmann::json e = {{"KHR_materials_transmission", {{"transmissionFactor", t}}}, {"KHR_materials_ior", {{"ior", 1.5}}}};
  if (solid) e["KHR_materials_volume"] = {{"thicknessFactor", 1.0}};
  return e;
}

// The slab seen straight down through a narrow lens (every ray within 0.2 degrees of the normal)
// under a white sky, path traced (deep enough that what the slab keeps inside is negligible).
std::string slabScene(const std::string& gltf, int spp) {
  nlohmann::json s = {{"camera", {{"position", {1, 6, -1}}, {"target", {1, 0, -1}}, {"up", {0, 0, -1}},
                                  {"fov_y", 0.4}, {"width", 16}, {"height", 16}}},
                      {"meshes", {{{"file", gltf}}}},
                      {"environment", {{"radiance", {1, 1, 1}}}},
                      {"render", {{"integrator", "path"}, {"spp", spp}, {"max_depth", 24}}}};
  return s.dump();
}

Film renderIndependent(const std::string& path, std::uint32_t seed) {
  std::vector<std::string> warnings;
  Scene s = loadScene(path, warnings);
  s.render.seed = seed;
  s.render.sampler = Sampler::Independent;
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(hostDeviceInfo(), {});
  RenderStats stats;
  return r.render(s, bvh, stats);
}

// The Fresnel reflectance of ior 1.5 at normal incidence, from either side.
const double kR = 0.04;

}  // namespace

// Under a sky of radiance 1, at normal incidence: a thin sheet reflects R' = 2R / (1 + R) (its
// inter-reflections summed) untinted and passes 1 - R' times the tint t, so the image is
// R' + (1 - R') t; a solid slab reflects R at its face and everything that enters leaves, crossing
// two interfaces (each multiplies by t): R + (1 - R) t^2. Tinting the reflection too (R' t +
// (1 - R') t) or once per solid (R + (1 - R) t) is tens of standard errors away.
TEST_CASE("glTF transmission tint: a thin sheet and a solid slab under a white sky (closed forms)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  for (const bool solid : {false, true}) {
    CAPTURE(solid);
    dir.write("slab.gltf", gltfWith(slabMesh(solid), kTint, 0.0f, 0.0f, transmission(1.0, solid)));
    dir.write("slab.json", slabScene("slab.gltf", 64));
    std::vector<std::string> warnings;
    const Scene scene = loadScene(dir.file("slab.json"), warnings);
    CHECK(scene.materials[0].kind == (solid ? MCL_MATERIAL_dielectric : MCL_MATERIAL_thin_dielectric));
    for (const std::string& w : warnings) CHECK(w.find("tint") == std::string::npos);  // read, not warned
    const Film film = renderIndependent(dir.file("slab.json"), 5);
    for (int c = 0; c < 3; ++c) {
      CAPTURE(c);
      const double t = kTint[c], r = solid ? kR : 2.0 * kR / (1.0 + kR);
      const double expect = solid ? r + (1.0 - r) * t * t : r + (1.0 - r) * t;
      const double wrongReflection = solid ? r * t + (1.0 - r) * t * t : t;
      const double wrongOnce = r + (1.0 - r) * t;
      const ImageEstimate e = imageEstimate(film, c);
      CAPTURE(e.mean);
      CAPTURE(expect);
      REQUIRE(e.standardError > 0.0);
      CHECK(std::fabs(e.mean - expect) / e.standardError < 4.0);
      CHECK(std::fabs(e.mean - wrongReflection) / e.standardError > 10.0);
      if (solid) CHECK(std::fabs(e.mean - wrongOnce) / e.standardError > 10.0);
    }
  }
}

// A partly transmissive material picks the glass per hit (transmission_mix.h): that glass is tinted
// as the factor-1 material's is. On the thin sheet, metallic 0, t = 0.5: the image is half the
// tinted sheet's closed form (above) and half the same material without transmission (rendered);
// the glass untinted (half of 1) is far off.
TEST_CASE("glTF transmission tint: the glass of a per-hit pick is tinted too" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("mix.gltf", gltfWith(slabMesh(false), kTint, 0.0f, 0.2f, transmission(0.5, false)));
  dir.write("rest.gltf", gltfWith(slabMesh(false), kTint, 0.0f, 0.2f, transmission(0.0, false)));
  dir.write("mix.json", slabScene("mix.gltf", 64));
  dir.write("rest.json", slabScene("rest.gltf", 64));
  std::vector<std::string> warnings;
  CHECK(loadScene(dir.file("mix.json"), warnings).materials[0].kind == MCL_MATERIAL_metal_rough);
  CHECK(loadScene(dir.file("rest.json"), warnings).materials[0].kind == MCL_MATERIAL_metal_rough);
  const Film mix = renderIndependent(dir.file("mix.json"), 6), rest = renderIndependent(dir.file("rest.json"), 7);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const double b = kTint[c], rs = 2.0 * kR / (1.0 + kR);
    const ImageEstimate m = imageEstimate(mix, c), r = imageEstimate(rest, c);
    const double expect = 0.5 * (rs + (1.0 - rs) * b) + 0.5 * r.mean, clear = 0.5 + 0.5 * r.mean;
    const double se = std::sqrt(m.standardError * m.standardError + 0.25 * r.standardError * r.standardError);
    CAPTURE(m.mean);
    CAPTURE(expect);
    CHECK(std::fabs(m.mean - expect) / se < 4.0);
    CHECK(std::fabs(m.mean - clear) / se > 10.0);
  }
}

// The sheet (base colour b, factor 1 x the transmissionTexture's R, r = 128 / 255; its G and B 1)
// over a lamp of radiance 1 facing it, under a black sky: the glass is picked with probability r
// and passes (1 - R') b of the lamp; the rest (metal_rough) reflects the black sky (the lamp lies
// behind it): r (1 - R') b. The factor alone (1) or the texture's G (1) is twice that.
TEST_CASE("glTF transmissionTexture: the factor times the texture's R, per hit (a sheet over a lamp)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("tr.png"), 4, 4, 3, [](int, int, int c) { return c == 0 ? 128 : 255; });
  nlohmann::json g = nlohmann::json::parse(gltfWith(slabMesh(false), kTint, 0.0f, 0.2f, transmission(1.0, false)));
  g["images"] = {{{"uri", "tr.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionTexture"] = {{"index", 0}};
  dir.write("sheet.gltf", g.dump());
  MeshData lamp = slabMesh(false);  // the same face 3 below the sheet, wider, facing up
  for (std::size_t k = 0; k < lamp.positions.size(); k += 3) {
    lamp.positions[k] = 1.0f + 4.0f * (lamp.positions[k] - 1.0f);
    lamp.positions[k + 1] = -2.0f;
    lamp.positions[k + 2] = -1.0f + 4.0f * (lamp.positions[k + 2] + 1.0f);
  }
  dir.write("lamp.gltf", gltfText(lamp, 0.0f, ""));
  nlohmann::json s = nlohmann::json::parse(slabScene("sheet.gltf", 64));
  s["meshes"].push_back({{"file", "lamp.gltf"}, {"material", {{"emission", {1, 1, 1}}}}});
  s["environment"]["radiance"] = {0, 0, 0};
  dir.write("sheet.json", s.dump());
  std::vector<std::string> warnings;
  const Scene scene = loadScene(dir.file("sheet.json"), warnings);
  CHECK(scene.materials[0].kind == MCL_MATERIAL_metal_rough);  // a pick per hit, not the whole kind
  CHECK_FALSE(scene.materials[0].transmissionTexture.empty());
  for (const std::string& w : warnings) CHECK(w.find("transmissionTexture") == std::string::npos);
  const Film film = renderIndependent(dir.file("sheet.json"), 8);
  const double r = 128.0 / 255.0, rs = 2.0 * kR / (1.0 + kR);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const double expect = r * (1.0 - rs) * kTint[c];
    const ImageEstimate e = imageEstimate(film, c);
    CAPTURE(e.mean);
    CAPTURE(expect);
    CHECK(std::fabs(e.mean - expect) / e.standardError < 4.0);
    CHECK(std::fabs(e.mean - expect / r) / e.standardError > 10.0);
  }
  // A transmissionTexture that is not a textureInfo: one line naming the key.
  g["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionTexture"] = {{"texCoord", 0}};
  dir.write("bad.gltf", g.dump());
  try {
    loadScene(dir.file("bad.gltf"), warnings);
    FAIL("loaded");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find("KHR_materials_transmission.transmissionTexture") != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
}

// The packet stages build the glass's tint in lanes (lane_frame's textured albedo, lane_bsdf's
// tint, the pick's flag) and read the transmissionTexture in lanes (lane_frame_attributes): byte
// for byte the host's, for a textured base colour on solid and thin glass, whole (the kind itself)
// and picked per hit (with a transmissionTexture whose R varies texel by texel), both samplers.
TEST_CASE("glTF transmission tint with a baseColorTexture: byte for byte the host backend's at W = 1, 4, 8, 16" *
          doctest::test_suite("cli")) {
  TempDir dir;
  writeImage8(dir.file("base.png"), 8, 8, 3, [](int x, int y, int c) { return (41 * x + 73 * y + 90 * c) % 256; });
  writeImage8(dir.file("tr.png"), 8, 8, 3, [](int x, int y, int c) { return c == 0 ? (29 * x + 67 * y) % 256 : 0; });
  const float base[3] = {0.9f, 0.8f, 0.7f};
  for (const bool solid : {true, false})
    for (const double t : {1.0, 0.6}) {
      nlohmann::json g = nlohmann::json::parse(gltfWith(tentMesh(), base, 0.0f, 0.3f, transmission(t, solid)));
      g["images"] = {{{"uri", "base.png"}}, {{"uri", "tr.png"}}};
      g["textures"] = {{{"source", 0}}, {{"source", 1}}};
      g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
      if (t < 1.0) g["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionTexture"] = {{"index", 1}};
      dir.write("glass.gltf", g.dump());
      nlohmann::json s = {{"camera", {{"position", {1.2, 3.5, -1}}, {"target", {1.2, 0, -1}}, {"up", {0, 0, -1}},
                                      {"fov_y", 45}, {"width", 12}, {"height", 10}}},
                          {"meshes", {{{"file", "glass.gltf"}}}},
                          {"environment", {{"radiance", {0.3, 0.2, 0.1}}}},
                          {"lights", {{{"type", "directional"}, {"direction", {0.3, -1, 0.2}}, {"irradiance", {2, 2, 2}}}}},
                          {"render", {{"integrator", "path"}, {"spp", 4}, {"max_depth", 6}}}};
      dir.write("glass.json", s.dump());
      for (const char* integrator : {"direct", "path"}) {
        const char* sampler = integrator[0] == 'd' ? "independent" : "sobol";
        CAPTURE(solid);
        CAPTURE(t);
        CAPTURE(integrator);
        const std::vector<std::string> common = {"render", dir.file("glass.json"), "-q", "--integrator", integrator,
                                                 "--sampler", sampler, "--overwrite"};
        checkLanesMatchHost(common, dir, {"1", "4", "8", "16"});
      }
    }
}

}  // namespace test_file_gltf_transmission_tint
