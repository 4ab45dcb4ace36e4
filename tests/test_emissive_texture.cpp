// test_emissive_texture.cpp: emission textures (Le = Ke x texture, shared/surface_texture.h
// material_emission; emitter weights, host/render/emitters.cpp): a quad whose emission texture is
// black but for one white square lights a floor as that square alone does (per-pixel z-test);
// light-only and BSDF-only direct sampling of it agree (the pdfs match the selection weights);
// only triangles whose emission is non-zero somewhere are emitters; the host backend and the
// OpenCL device give the same bits; glTF emissiveTexture and a scene file's emission_texture load;
// the scene digest follows the texture's content.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "mesh_files.h"
#include "render/device_materials.h"
#include "render/emitters.h"
#include "render/triangle_shading.h"
#include "render/wavefront.h"
#include "scene/scene_digest.h"
#include "test_images.h"
#include "test_scenes.h"
#include "texture/scene_textures.h"

namespace test_file_emissive_texture {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// The quad a, b, c, d (counter-clockwise from its front) with texture coordinates ta .. td.
void addUvQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec2 ta, glm::vec2 tb,
               glm::vec2 tc, glm::vec2 td, std::uint32_t material) {
  s.triangles.push_back(SceneTriangle{{a, b, c}, material, {}, {ta, tb, tc}, kHasUv});
  s.triangles.push_back(SceneTriangle{{a, c, d}, material, {}, {ta, tc, td}, kHasUv});
}

// 16 x 16 texels, white where texel x in [2, 6) and y in [10, 14) (y = 0 the bottom row): u in
// [0.125, 0.375), v in [0.625, 0.875), clear of the quad's diagonal v = u by more than a texel.
void writeSquareTexture(const std::string& path, bool white = true) {
  writeImage8(path, 16, 16, 3, [white](int x, int y, int) {
    const int row = 15 - y;  // the image's rows run top to bottom
    return white && x >= 2 && x < 6 && row >= 10 && row < 14 ? 255 : 0;
  });
}

// A floor y = 0 (albedo 0.5) seen from the side, lit from y = 0.5 by a downward-facing emitter:
// the 1 x 1 quad over [-0.5, 0.5]^2 textured with `texture` (u along x, v along z), or (texture
// empty) the untextured square x in [-0.375, -0.125], z in [0.125, 0.375] where that texture is white.
Scene floorUnderEmitter(const std::string& texture, int spp) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<floor under an emissive texture>";
  s.materials = {MaterialDesc{"floor", glm::vec3(0.5f)}, MaterialDesc{"lamp", glm::vec3(0.0f), glm::vec3(16.0f)}};
  addQuad(s, {-1.5f, 0, -1.5f}, {-1.5f, 0, 1.5f}, {1.5f, 0, 1.5f}, {1.5f, 0, -1.5f}, 0);
  const float y = 0.5f;
  if (!texture.empty()) {
    s.materials[1].emissionTexture = texture;
    addUvQuad(s, {-0.5f, y, -0.5f}, {0.5f, y, -0.5f}, {0.5f, y, 0.5f}, {-0.5f, y, 0.5f}, {0, 0}, {1, 0}, {1, 1},
              {0, 1}, 1);
  } else {
    addQuad(s, {-0.375f, y, 0.125f}, {-0.125f, y, 0.125f}, {-0.125f, y, 0.375f}, {-0.375f, y, 0.375f}, 1);
  }
  s.camera.position = {0.0f, 0.35f, 2.5f};  // below the lamp's plane: it sees the floor only
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = 50.0f;
  s.camera.width = 16;
  s.camera.height = 12;
  s.render.spp = spp;
  s.render.integrator = Integrator::Direct;
  finishScene(s);
  return s;
}

Film render(const Scene& scene, DirectSampling strategy, bool host = true, std::uint32_t seed = 1) {
  static const DeviceInfo defaultDevice = selectDevice("");
  Scene s = scene;
  s.render.directSampling = strategy;
  s.render.seed = seed;
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer renderer(host ? hostDeviceInfo() : defaultDevice, {});
  RenderStats stats;
  return renderer.render(s, bvh, stats);
}

// Per-pixel-channel z-scores of two independent films: the share with |z| > 4 and the mean z.
struct ZSummary {
  double over4 = 0.0, meanZ = 0.0;
  int channels = 0;
};
ZSummary zScores(const Film& a, const Film& b) {
  requireIndependentSamples(a);
  requireIndependentSamples(b);
  ZSummary out;
  double sum = 0.0;
  int over = 0;
  for (std::size_t p = 0; p < a.pixelCount(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double va = a.variance(p, c) / double(a.count[p]), vb = b.variance(p, c) / double(b.count[p]);
      const double d = a.meanOf(p, c) - b.meanOf(p, c);
      if (va + vb == 0.0) {
        CHECK(d == 0.0);
        continue;
      }
      const double z = d / std::sqrt(va + vb);
      sum += z;
      over += std::fabs(z) > 4.0;
      ++out.channels;
    }
  out.over4 = double(over) / double(out.channels);
  out.meanZ = sum / double(out.channels);
  return out;
}

// The emitter table of a loaded scene with its textures (as the renderer builds it).
EmitterTable texturedTable(const Scene& s) {
  std::vector<std::string> warnings;
  const SceneTextures st = loadSceneTextures(s, kDefaultTextureBudget, warnings);
  const Bvh bvh = buildBvh(s.triangles);
  std::vector<Material> mats = deviceMaterials(s.materials, &st);
  std::vector<TriangleShading> sh = buildTriangleShading(s.triangles, bvh);
  EmissionTextures e;
  e.materials = &mats;
  e.shading = &sh;
  e.tables = make_texture_tables(st.textures.data(), st.levels.data(), st.texels.data());
  return buildEmitterTable(bvh, s.materials, &e);
}

}  // namespace

TEST_CASE("emission texture: a lamp black but for a white square lights the floor as the square alone does" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeSquareTexture(dir.file("square.png"));
  const Scene textured = floorUnderEmitter(dir.file("square.png"), 256);
  const Scene plain = floorUnderEmitter("", 256);
  CHECK(texturedTable(textured).emitters.size() == 1);  // the triangle holding the square only
  const Film a = render(textured, DirectSampling::Mis, true, 1), b = render(plain, DirectSampling::Mis, true, 2);
  const ImageEstimate ea = imageEstimate(a, 1), eb = imageEstimate(b, 1);
  CHECK(eb.mean > 0.01);  // the floor is lit
  const ZSummary z = zScores(a, b);
  MESSAGE("image mean " << ea.mean << " +- " << ea.standardError << " vs " << eb.mean << " +- " << eb.standardError
                        << "; |z| > 4 on " << z.over4 * 100 << "% of " << z.channels << ", mean z " << z.meanZ);
  CHECK(std::fabs(ea.mean - eb.mean) < 4.0 * std::hypot(ea.standardError, eb.standardError));
  CHECK(z.over4 <= 0.01);
  CHECK(std::fabs(z.meanZ) < 0.25);
}

TEST_CASE("emission texture: light-only and BSDF-only direct sampling agree (pdfs match the selection weights)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeSquareTexture(dir.file("square.png"));
  const Scene s = floorUnderEmitter(dir.file("square.png"), 512);
  const Film light = render(s, DirectSampling::Light, true, 3), brdf = render(s, DirectSampling::Brdf, true, 4);
  for (int c = 0; c < 3; ++c) {
    const ImageEstimate el = imageEstimate(light, c), eb = imageEstimate(brdf, c);
    const double z = (el.mean - eb.mean) / std::hypot(el.standardError, eb.standardError);
    MESSAGE("channel " << c << ": light " << el.mean << " +- " << el.standardError << ", brdf " << eb.mean << " +- "
                       << eb.standardError << ", z " << z);
    CHECK(std::fabs(z) < 4.0);
  }
}

TEST_CASE("emission texture: the host backend and the OpenCL device give the same bits" * doctest::test_suite("opencl")) {
  TempDir dir;
  writeSquareTexture(dir.file("square.png"));
  Scene s = floorUnderEmitter(dir.file("square.png"), 8);
  s.camera.position = {0.0f, 0.25f, 2.5f};  // below the lamp's plane, looking up a little: the lamp's
  s.camera.target = {0.0f, 0.3f, 0.0f};     // front (the white square among black) and the floor
  finishScene(s);
  for (Integrator in : {Integrator::Direct, Integrator::Path}) {
    s.render.integrator = in;
    const Film h = render(s, DirectSampling::Mis, true, 5), d = render(s, DirectSampling::Mis, false, 5);
    REQUIRE(h.pixelCount() == d.pixelCount());
    double lit = 0.0;
    for (std::size_t p = 0; p < h.pixelCount(); ++p) {
      CHECK(h.mean[p] == d.mean[p]);
      lit += h.mean[p].y;
    }
    CHECK(lit > 0.0);  // the white square is in view
  }
}

TEST_CASE("emission texture: only triangles whose emission is non-zero somewhere are emitters" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  // A 4 x 4 grid of quads (32 triangles) over UV [0, 1]^2, a 32 x 32 texture white only on texels
  // x in [13, 15), y in [17, 19): inside grid cell (1, 2), below its diagonal (one triangle).
  writeImage8(dir.file("dot.png"), 32, 32, 3, [](int x, int y, int) {
    const int row = 31 - y;
    return x >= 13 && x < 15 && row >= 17 && row < 19 ? 255 : 0;
  });
  writeImage8(dir.file("black.png"), 32, 32, 3, [](int, int, int) { return 0; });
  writeImage8(dir.file("white.png"), 32, 32, 3, [](int, int, int) { return 255; });
  const auto grid = [&](const std::string& texture) {
    Scene s;
    s.path = "<grid>";
    s.materials = {MaterialDesc{"lamp", glm::vec3(0.5f), glm::vec3(1.0f)}};
    s.materials[0].emissionTexture = texture;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const float u0 = 0.25f * float(i), v0 = 0.25f * float(j), u1 = u0 + 0.25f, v1 = v0 + 0.25f;
        addUvQuad(s, {u0, v0, 0}, {u1, v0, 0}, {u1, v1, 0}, {u0, v1, 0}, {u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}, 0);
      }
    finishScene(s);
    return s;
  };
  CHECK(texturedTable(grid(dir.file("dot.png"))).emitters.size() == 1);
  CHECK(texturedTable(grid(dir.file("black.png"))).emitters.empty());
  CHECK(texturedTable(grid(dir.file("white.png"))).emitters.size() == 32);
  CHECK(buildEmitterTable(buildBvh(grid("").triangles), grid("").materials).emitters.size() == 32);
  // The dot's triangle: weight area x mean luminance, the mean below 1 (the dot covers part of it).
  const EmitterTable dot = texturedTable(grid(dir.file("dot.png")));
  CHECK(dot.totalPower > 0.0f);
  CHECK(dot.totalPower < 0.5f * 0.0625f * 0.5f);
}

TEST_CASE("emission texture: glTF emissiveTexture x emissiveFactor, black factor or texture emits nothing" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("black.png"), 4, 4, 3, [](int, int, int) { return 0; });
  writeImage8(dir.file("white.png"), 4, 4, 3, [](int, int, int) { return 255; });
  const auto load = [&](const std::string& image, double factor) {
    nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), 0.5f, ""));
    g["images"] = {{{"uri", image}}};
    g["textures"] = {{{"source", 0}}};
    g["materials"][0]["emissiveTexture"] = {{"index", 0}};
    g["materials"][0]["emissiveFactor"] = {factor, factor, factor};
    dir.write("m.gltf", g.dump());
    std::vector<std::string> warnings;
    Scene s = loadScene(dir.file("m.gltf"), warnings);
    for (const std::string& w : warnings) CHECK(w.find("emissiveTexture") == std::string::npos);
    return s;
  };
  const Scene white = load("white.png", 1.0), blackFactor = load("white.png", 0.0), blackTexture = load("black.png", 1.0);
  CHECK(white.materials[0].emissionTexture == dir.file("white.png"));
  CHECK(texturedTable(white).emitters.size() == white.triangles.size());
  CHECK(blackFactor.materials[0].emissionTexture.empty());
  CHECK_FALSE(hasEmitter(blackFactor));
  CHECK(texturedTable(blackFactor).emitters.empty());
  CHECK(texturedTable(blackTexture).emitters.empty());
  // The digest (and so the checkpoints' render key) follows the emission texture's content.
  CHECK(sceneDigest(white) != sceneDigest(blackTexture));
}

TEST_CASE("emission texture: the scene file's emission_texture and MTL map_Ke" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("glow.png"), 4, 4, 3, [](int, int, int) { return 255; });
  dir.write("q.obj", "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl lamp\nf 1/1 2/2 3/3\n");
  dir.write("q.mtl", "newmtl lamp\nKd 0 0 0\nmap_Ke glow.png\n");
  std::vector<std::string> warnings;
  Scene obj = loadScene(dir.file("q.obj"), warnings);
  for (const std::string& w : warnings) CHECK(w.find("map_Ke") == std::string::npos);
  CHECK(obj.materials[0].emissionTexture == dir.file("glow.png"));
  CHECK(obj.materials[0].emission == glm::vec3(1.0f));  // no Ke: the texture as it is
  // A bare model whose only emission is textured keeps the default sky (untextured Ke, a light
  // fixture, does not: test_scene's "bare OBJ with an emitter").
  CHECK(obj.environment.enabled);
  dir.write("s.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 40, "width": 8, "height": 8}, "meshes": [{"file": "q.obj", "material": {"emission": [2, 2, 2], "emission_texture": "glow.png"}}]})");
  const Scene json = loadScene(dir.file("s.json"), warnings);
  CHECK(json.materials.back().emissionTexture == dir.file("glow.png"));
  CHECK(json.materials.back().emission == glm::vec3(2.0f));
  dir.write("bad.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 40, "width": 8, "height": 8}, "meshes": [{"file": "q.obj", "material": {"emission_texture": "missing.png"}}]})");
  CHECK_THROWS_WITH(loadScene(dir.file("bad.json"), warnings), doctest::Contains("meshes[0].material.emission_texture"));
}

}  // namespace test_file_emissive_texture
