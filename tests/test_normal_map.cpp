// test_normal_map.cpp: tangent-space normal maps (kernels/shared/normal_map.h; texels decoded on
// the host, texture/scene_textures.cpp): a plane whose map holds one tilted texel, lit by a
// directional (delta) light under direct light sampling, has radiance exactly rho/pi E max(0, n.l)
// with n = normalize(t.x dP/du + t.y dP/dv + t.z N) for UV maps rotated and mirrored (handedness),
// and with the glTF scale; glTF normalTexture, MTL norm (-bm) and a scene file's normal_texture /
// normal_scale load; a missing normal texture and a scale that is not a number are one line, exit 2.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "scene/builtin_scenes.h"
#include "test_images.h"
#include "test_scenes.h"
#include "util/errors.h"

namespace test_file_normal_map {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
const glm::vec3 kRho(0.5f, 0.6f, 0.7f);
const glm::vec3 kE(0.7f, 0.4f, 0.2f);
// The texel: the unit normal tilted 30 degrees from N toward (cos 60, sin 60) of the tangent plane.
const int kTexel[3] = {159, 183, 238};

double decode(int c8, double scale) { return (2.0 * c8 / 255.0 - 1.0) * scale; }

// The floor y = 0 over [-2, 2]^2 whose UV at (x, z) is uvOf(x, z) (linear), under a directional
// light along lightDir, seen straight down from 0.05 above (0.2, 0, -0.1) (every pixel sees the
// floor); material normal map `texture` with `scale` (none when empty).
template <class UV>
Scene plane(const std::string& texture, float scale, UV uvOf, glm::vec3 lightDir, int spp = 4) {
  Scene s;
  s.path = "<normal-mapped floor>";
  MaterialDesc m("floor", kRho, glm::vec3(0.0f));
  m.normalTexture = texture;
  m.normalScale = scale;
  s.materials = {m};
  const glm::vec3 a(-2, 0, 2), b(2, 0, 2), c(2, 0, -2), d(-2, 0, -2);
  const auto uv = [&](glm::vec3 p) { return uvOf(p.x, p.z); };
  s.triangles.push_back(SceneTriangle{{a, b, c}, 0, {}, {uv(a), uv(b), uv(c)}, kHasUv});
  s.triangles.push_back(SceneTriangle{{a, c, d}, 0, {}, {uv(a), uv(c), uv(d)}, kHasUv});
  const glm::vec3 at(0.2f, 0.0f, -0.1f);
  s.camera.position = at + glm::vec3(0, 0.05f, 0);
  s.camera.target = at;
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 0.01f;
  s.camera.width = s.camera.height = 4;
  s.render.spp = spp;
  s.render.integrator = Integrator::Direct;
  s.render.directSampling = DirectSampling::Light;
  LightDesc l;
  l.kind = PunctualKind::Directional;
  l.direction = lightDir;
  l.color = kE;
  s.lights = {l};
  finishScene(s);
  return s;
}

Film render(const Scene& s) {
  static const DeviceInfo device = selectDevice("");
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(s, bvh, stats);
}

// Every pixel and channel of f equals rho/pi E max(0, n.l) to half-float texel precision.
void checkRadiance(const Film& f, glm::dvec3 n, glm::dvec3 l) {
  const double cosine = std::max(0.0, glm::dot(glm::normalize(n), glm::normalize(l)));
  MESSAGE("n.l = " << cosine);
  for (std::size_t p = 0; p < f.pixelCount(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double expected = double(kRho[c]) / kPi * double(kE[c]) * cosine;
      CHECK(f.variance(p, c) <= 1e-12 * expected * expected);  // one value: zero variance
      CHECK(f.meanOf(p, c) == doctest::Approx(expected).epsilon(1.5e-3));
    }
}

}  // namespace

TEST_CASE("normal map: a constant tilted texel under a directional light gives rho/pi E max(0, n.l) for rotated and mirrored UVs" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeImage8(dir.file("n.png"), 4, 4, 3, [](int, int, int c) { return kTexel[c]; });
  const glm::dvec3 N(0, 1, 0);
  const glm::vec3 lightDir = glm::normalize(glm::vec3(-0.6f, -1.0f, 0.3f));  // light travels along this
  const glm::dvec3 l = -glm::dvec3(lightDir);
  struct Map {
    const char* name;
    glm::dvec2 du, dv;  // the UV's gradient: u = dot(du, (x, z)), v = dot(dv, (x, z))
  };
  const double c30 = std::cos(kPi / 6), s30 = std::sin(kPi / 6);
  const Map maps[] = {
      {"u along x, v along -z", {1, 0}, {0, -1}},
      {"rotated 90 degrees", {0, -1}, {-1, 0}},
      {"rotated 30 degrees, scaled by 2", {2 * c30, 2 * s30}, {2 * s30, -2 * c30}},
      {"mirrored: v along +z (left-handed)", {1, 0}, {0, 1}},
      {"mirrored and rotated 90 degrees", {0, 1}, {-1, 0}},
  };
  for (float scale : {1.0f, 0.6f}) {
    for (const Map& mp : maps) {
      CAPTURE(std::string(mp.name));
      CAPTURE(scale);
      const auto uvOf = [&](float x, float z) {
        return glm::vec2(float(mp.du.x * x + mp.du.y * z) + 0.5f, float(mp.dv.x * x + mp.dv.y * z) + 0.5f);
      };
      // dP/du and dP/dv of this (orthogonal) map in world space: the inverse of the 2x2 gradient.
      const double det = mp.du.x * mp.dv.y - mp.du.y * mp.dv.x;
      const glm::dvec3 dPdu(mp.dv.y / det, 0, -mp.dv.x / det), dPdv(-mp.du.y / det, 0, mp.du.x / det);
      const glm::dvec3 n = glm::normalize(dPdu) * decode(kTexel[0], scale) +
                           glm::normalize(dPdv) * decode(kTexel[1], scale) + N * decode(kTexel[2], 1.0);
      checkRadiance(render(plane(dir.file("n.png"), scale, uvOf, lightDir)), n, l);
    }
  }
  // Without the map: the plane's own normal (and the tilt makes a difference the check can see).
  const auto flatUv = [](float x, float z) { return glm::vec2(x, -z); };
  checkRadiance(render(plane("", 1.0f, flatUv, lightDir)), N, l);
  // A light the mapped normal faces away from is 0, though the plane faces it.
  const glm::vec3 grazing = glm::normalize(glm::vec3(0.9f, -0.15f, -0.6f));
  const glm::dvec3 n1 = glm::dvec3(1, 0, 0) * decode(kTexel[0], 1) + glm::dvec3(0, 0, -1) * decode(kTexel[1], 1) +
                        N * decode(kTexel[2], 1);
  REQUIRE(glm::dot(glm::normalize(n1), -glm::dvec3(grazing)) < 0.0);
  const Film dark = render(plane(dir.file("n.png"), 1.0f, flatUv, grazing));
  for (std::size_t p = 0; p < dark.pixelCount(); ++p) CHECK(dark.meanOf(p, 1) == 0.0);
}

TEST_CASE("normal map: glTF normalTexture (scale), MTL norm (-bm) and a scene file's normal_texture load" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeImage8(dir.file("n.png"), 4, 4, 3, [](int, int, int c) { return kTexel[c]; });
  nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), 0.5f, ""));
  g["images"] = {{{"uri", "n.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["normalTexture"] = {{"index", 0}, {"scale", 0.75}};
  dir.write("m.gltf", g.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("m.gltf"), warnings);
  for (const std::string& w : warnings) CHECK(w.find("normalTexture") == std::string::npos);
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].normalTexture == dir.file("n.png"));
  CHECK(s.materials[0].normalScale == 0.75f);

  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n");
  dir.write("m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnorm -bm 0.5 n.png\n");
  warnings.clear();
  const Scene o = loadScene(dir.file("m.obj"), warnings);
  for (const std::string& w : warnings) CHECK(w.find("norm") == std::string::npos);
  REQUIRE(o.materials.size() == 1);
  CHECK(o.materials[0].normalTexture == dir.file("n.png"));
  CHECK(o.materials[0].normalScale == 0.5f);

  dir.write("s.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 40, "width": 8, "height": 8},
    "meshes": [{"file": "m.obj", "material": {"normal_texture": "n.png", "normal_scale": 2}}]})");
  warnings.clear();
  const Scene j = loadScene(dir.file("s.json"), warnings);
  REQUIRE(!j.materials.empty());  // the override is a material of its own, the last
  CHECK(j.materials.back().normalTexture == dir.file("n.png"));
  CHECK(j.materials.back().normalScale == 2.0f);
}

TEST_CASE("normal map: a missing normal texture or a scale that is not a number is one line, exit 2, nothing written" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeImage8(dir.file("n.png"), 4, 4, 3, [](int, int, int c) { return kTexel[c]; });
  nlohmann::json g = nlohmann::json::parse(gltfText(tentMesh(), 0.5f, ""));
  g["images"] = {{{"uri", "missing.png"}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["normalTexture"] = {{"index", 0}};
  dir.write("missing.gltf", g.dump());
  g["images"] = {{{"uri", "n.png"}}};
  g["materials"][0]["normalTexture"] = {{"index", 0}, {"scale", "big"}};
  dir.write("scale.gltf", g.dump());
  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n");
  dir.write("m.mtl", "newmtl a\nnorm gone.png\n");
  dir.write("s.json", R"({"meshes": [{"file": "m.obj", "material": {"normal_texture": "n.png", "normal_scale": "x"}}]})");
  const struct {
    const char* file;
    std::string needle;
  } cases[] = {
      {"missing.gltf", "missing.png"},
      {"scale.gltf", "materials[0].normalTexture.scale: must be a number"},
      {"m.obj", "gone.png"},
      {"s.json", "meshes[0].material.normal_scale"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.file);
    const CliResult r = runMontecl({"render", dir.file(c.file), "-o", dir.file("out.png"), "-q"});
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(c.needle) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
  }
}

}  // namespace test_file_normal_map
