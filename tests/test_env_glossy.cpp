// test_env_glossy.cpp: the environment light and the glossy lobe through the real kernels
// (direct integrator): a convex object of albedo a under a constant environment E shows exactly
// a E with BSDF sampling (zero variance) and within 4 standard errors with light and MIS sampling;
// camera misses see E; an environment map is importance sampled with a lower variance than
// cosine (BSDF) sampling at equal spp; light, BSDF and MIS sampling agree on a glossy plate lit by
// an area light and by an environment map; bad input. The path integrator: the environment
// furnace, --max-depth 2 = direct mis with glossy + environment + area light, a glossy furnace.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "image/exr_layers.h"
#include "render/wavefront.h"
#include "stats.h"
#include "test_scenes.h"

namespace test_file_env_glossy {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

Film renderDirect(Scene scene, const std::string& strategy) {
  static const DeviceInfo device = selectDevice("");
  scene.render.integrator = montecl::Integrator::Direct;
  scene.render.sampler = montecl::Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  scene.render.directSampling = directSamplingNames().at(strategy);
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

const glm::vec3 kE(1.0f, 0.5f, 0.25f);
const float kA = 0.6f;

// A unit cube at the origin (albedo kA) under the constant environment kE, seen face-on through a
// narrow field of view (every pixel on the face z = 0.5), or looking away from it (no geometry).
Scene cubeScene(bool lookAway) {
  Scene s;
  s.path = "<cube>";
  s.materials = {MaterialDesc{"cube", glm::vec3(kA), glm::vec3(0.0f)}};
  const float h = 0.5f;
  const glm::vec3 p[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h},
                          {-h, -h, h},  {h, -h, h},  {h, h, h},  {-h, h, h}};
  addQuad(s, p[4], p[5], p[6], p[7]);
  addQuad(s, p[1], p[0], p[3], p[2]);
  addQuad(s, p[5], p[1], p[2], p[6]);
  addQuad(s, p[0], p[4], p[7], p[3]);
  addQuad(s, p[7], p[6], p[2], p[3]);
  addQuad(s, p[0], p[1], p[5], p[4]);
  s.camera.position = {0.05f, 0.1f, 3.0f};
  s.camera.target = lookAway ? glm::vec3(0.05f, 0.1f, 6.0f) : glm::vec3(0.05f, 0.1f, 0.0f);
  s.camera.fovY = 5.0f;
  s.camera.width = s.camera.height = 4;
  s.render.spp = 256;
  s.environment.enabled = true;
  s.environment.radiance = kE;
  finishScene(s);
  return s;
}

// Writes a 32 x 16 sky (dim blue above, dark ground below, a small bright sun) as an EXR.
std::string writeSky(const TempDir& dir) {
  LayeredImage img;
  img.width = 32;
  img.height = 16;
  std::vector<float> rgb[3];
  for (auto& p : rgb) p.assign(img.pixelCount(), 0.0f);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      glm::vec3 c = y < 8 ? glm::vec3(0.2f, 0.3f, 0.6f) : glm::vec3(0.05f, 0.04f, 0.03f);
      if (y >= 3 && y <= 4 && x >= 20 && x <= 21) c = glm::vec3(200.0f, 180.0f, 150.0f);
      for (int k = 0; k < 3; ++k) rgb[k][std::size_t(y) * 32 + x] = c[k];
    }
  img.set("R", rgb[0]);
  img.set("G", rgb[1]);
  img.set("B", rgb[2]);
  const std::string path = dir.file("sky.exr");
  writeLayeredExr(path, img);
  return path;
}

// Pooled z of the difference of two images' means (channel c).
double zDiff(const Film& a, const Film& b, int c) {
  ImageEstimate x = imageEstimate(a, c), y = imageEstimate(b, c);
  return (x.mean - y.mean) / std::hypot(x.standardError, y.standardError);
}

// Mean over pixels of the variance of one sample (channel c).
double meanVariance(const Film& f, int c) {
  double sum = 0.0;
  for (std::size_t p = 0; p < f.mean.size(); ++p) sum += f.variance(p, c);
  return sum / double(f.mean.size());
}

}  // namespace

TEST_CASE("environment furnace: a convex object of albedo a under constant E shows a E; misses see E" * doctest::test_suite("opencl")) {
  const Scene face = cubeScene(false), away = cubeScene(true);
  for (const char* strategy : {"brdf", "light", "mis"}) {
    INFO(strategy);
    const Film f = renderDirect(face, strategy);
    for (int c = 0; c < 3; ++c) {
      const double expected = double(kA) * kE[c];
      ImageEstimate e = imageEstimate(f, c);
      INFO("channel " << c << ": expected " << expected << ", got " << e.mean << " +- " << e.standardError);
      if (std::string(strategy) == "brdf") {  // every BSDF ray escapes: weight a, radiance E
        for (std::size_t p = 0; p < f.mean.size(); ++p) CHECK(f.meanOf(p, c) == doctest::Approx(expected).epsilon(1e-6));
        CHECK(e.standardError < 1e-6);
      } else {
        CHECK(e.standardError > 0.0);
        CHECK(std::fabs(e.mean - expected) < 4.0 * e.standardError);
      }
    }
    const Film b = renderDirect(away, strategy);
    for (std::size_t p = 0; p < b.mean.size(); ++p)
      for (int c = 0; c < 3; ++c) CHECK(b.meanOf(p, c) == double(kE[c]));
  }
}

TEST_CASE("environment map: importance sampling has lower variance than BSDF sampling at equal spp" * doctest::test_suite("opencl")) {
  TempDir dir;
  Scene s = floorScene({0.3f, 0.0f, 0.2f}, 1.0f, 30.0f, 8, 256);
  s.environment.enabled = true;
  s.environment.file = writeSky(dir);
  s.environment.rotateYDegrees = 40.0f;
  const Film light = renderDirect(s, "light"), brdf = renderDirect(s, "brdf"), mis = renderDirect(s, "mis");
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": light " << imageMean(light, c) << " var " << meanVariance(light, c) << "; brdf "
                    << imageMean(brdf, c) << " var " << meanVariance(brdf, c) << "; mis "
                    << imageMean(mis, c) << " var " << meanVariance(mis, c));
    CHECK(std::fabs(zDiff(light, brdf, c)) < 4.0);
    CHECK(std::fabs(zDiff(mis, brdf, c)) < 4.0);
    CHECK(meanVariance(light, c) < 0.2 * meanVariance(brdf, c));
    CHECK(meanVariance(mis, c) < 0.5 * meanVariance(brdf, c));
  }
}

TEST_CASE("glossy plate: light, BSDF and MIS sampling agree (area light and environment map)" * doctest::test_suite("opencl")) {
  TempDir dir;
  for (bool env : {false, true}) {
    Scene s;
    s.path = "<glossy plate>";
    MaterialDesc plate{"plate", glm::vec3(0.2f, 0.25f, 0.3f), glm::vec3(0.0f)};
    plate.specular = glm::vec3(0.6f, 0.5f, 0.4f);
    plate.specularExponent = 100.0f;  // alpha ~ 0.14
    s.materials = {plate, MaterialDesc{"light", glm::vec3(0.0f), glm::vec3(5.0f, 4.0f, 3.0f)}};
    addFloor(s, 0);
    if (!env) addQuad(s, {-0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, {-0.5f, 1.0f, 0.5f}, 1);  // faces down
    else {
      s.environment.enabled = true;
      s.environment.file = writeSky(dir);
    }
    s.camera.position = {-1.0f, 1.0f, 0.1f};  // near the mirror direction of the light
    s.camera.target = {-0.5f, 0.0f, 0.1f};
    s.camera.fovY = 20.0f;
    s.camera.width = s.camera.height = 8;
    s.render.spp = 512;
    finishScene(s);
    const Film light = renderDirect(s, "light"), brdf = renderDirect(s, "brdf"), mis = renderDirect(s, "mis");
    for (int c = 0; c < 3; ++c) {
      INFO(std::string(env ? "environment" : "area light") << ", channel " << c << ": light " << imageMean(light, c)
                                                << " brdf " << imageMean(brdf, c) << " mis "
                                                << imageMean(mis, c));
      CHECK(imageMean(mis, c) > 0.01);
      CHECK(std::fabs(zDiff(light, brdf, c)) < 4.0);
      CHECK(std::fabs(zDiff(mis, brdf, c)) < 4.0);
      CHECK(std::fabs(zDiff(mis, light, c)) < 4.0);
    }
  }
}

namespace {

// A scene file with one quad (material from quad.mtl) and the given "environment" JSON (none if
// empty), written to dir; returns its path.
std::string writeScene(const TempDir& dir, const std::string& environment, const std::string& mtl) {
  dir.write("quad.mtl", "newmtl m\n" + mtl);
  dir.write("quad.obj", "mtllib quad.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nusemtl m\nf 1 2 3 4\n");
  dir.write("scene.json", std::string("{\"camera\": {\"position\": [0, 2, 0.1], \"target\": [0, 0, 0], \"fov_y\": 40, ") +
                              "\"width\": 8, \"height\": 8}, \"meshes\": [{\"file\": \"quad.obj\"}], " +
                              "\"render\": {\"integrator\": \"direct\", \"spp\": 2}" +
                              (environment.empty() ? "" : ", \"environment\": " + environment) + "}");
  return dir.file("scene.json");
}

}  // namespace

TEST_CASE("cli: bad environment and glossy input: one line, exit 2, no output" * doctest::test_suite("cli sanitize")) {
  struct Case {
    std::string environment, mtl, needle;
  };
  const std::vector<Case> cases = {
      {R"({"file": "missing.exr"})", "Kd 0.5 0.5 0.5\n", "environment.file"},
      {R"({"file": "notimage.exr"})", "Kd 0.5 0.5 0.5\n", "environment.file"},
      {R"({"file": "folder"})", "Kd 0.5 0.5 0.5\n", "environment.file"},
      {R"({"radiance": [1, 1, 1], "scale": -1})", "Kd 0.5 0.5 0.5\n", "environment.scale"},
      {R"({"radiance": [1, -1, 1]})", "Kd 0.5 0.5 0.5\n", "environment.radiance"},
      {R"({"scale": 2})", "Kd 0.5 0.5 0.5\n", "environment"},
      {"", "Kd 0.5 0.5 0.5\nKs 1.5 0 0\n", "Ks"},
      {"", "Kd 0.5 0.5 0.5\nKs -0.1 0 0\n", "Ks"},
      {"", "Kd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs -1\n", "Ns"},
  };
  for (const Case& c : cases) {
    TempDir dir;
    dir.write("notimage.exr", "this is not an image\n");
    std::filesystem::create_directory(dir.file("folder"));
    const std::string scene = writeScene(dir, c.environment, c.mtl);
    CliResult r = runMontecl({"render", scene, "-q", "-o", dir.file("out.png")});
    INFO(c.environment << " / " << c.mtl << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(c.needle) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(dir.file("out.png")));
  }
}

TEST_CASE("cli: Kd + Ks above 1 is scaled down with one warning naming the file; an environment map renders" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  LayeredImage img;
  img.width = 8;
  img.height = 4;
  img.set("R", std::vector<float>(32, 1.0f));
  img.set("G", std::vector<float>(32, 0.5f));
  img.set("B", std::vector<float>(32, 0.25f));
  writeLayeredExr(dir.file("sky.exr"), img);
  const std::string scene = writeScene(dir, R"({"file": "sky.exr", "scale": 2, "rotate_y": 30})",
                                       "Kd 0.8 0.8 0.8\nKs 0.5 0.5 0.5\nNs 50\n");
  CliResult r = runMontecl({"render", scene, "-o", dir.file("out.pfm"), "--spp", "4"});
  INFO(r.err);
  CHECK(r.exitCode == 0);
  // Named by the MTL and the line of the material's Ks, where the fix goes.
  CHECK(r.err.find(dir.file("quad.mtl") + ": line 3: material 'm': Kd + Ks > 1, both scaled by 0.769") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("out.pfm")));
}

// --- the path integrator ----------------------------------------------------------------------
namespace {

Film renderPath(Scene scene, int maxDepth) {
  static const DeviceInfo device = selectDevice("");
  scene.render.integrator = montecl::Integrator::Path;
  scene.render.sampler = montecl::Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  scene.render.maxDepth = maxDepth;
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, {});
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

// Per-pixel |z| > 4 count between two films (channel c).
int pixelsApart(const Film& a, const Film& b, int c) {
  requireIndependentSamples(a);
  requireIndependentSamples(b);
  int apart = 0;
  for (std::size_t p = 0; p < a.mean.size(); ++p) {
    const double se = std::sqrt(a.variance(p, c) / double(a.count[p]) + b.variance(p, c) / double(b.count[p]));
    const double d = a.meanOf(p, c) - b.meanOf(p, c);
    if (std::fabs(d) > 4.0 * se + 1e-6) ++apart;
  }
  return apart;
}

}  // namespace

TEST_CASE("path: environment furnace: a convex cube of albedo a under constant E shows a E, misses E" * doctest::test_suite("opencl")) {
  const Film f = renderPath(cubeScene(false), -1);
  for (int c = 0; c < 3; ++c) {
    ImageEstimate e = imageEstimate(f, c);
    INFO("channel " << c << ": " << e.mean << " +- " << e.standardError);
    CHECK(e.standardError > 0.0);
    CHECK(std::fabs(e.mean - double(kA) * kE[c]) < 4.0 * e.standardError);
  }
  const Film b = renderPath(cubeScene(true), -1);
  for (std::size_t p = 0; p < b.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) CHECK(b.meanOf(p, c) == double(kE[c]));
}

TEST_CASE("path: --max-depth 2 equals direct mis on a glossy plate under an environment map and an area light" * doctest::test_suite("opencl")) {
  TempDir dir;
  Scene s;
  s.path = "<glossy plate>";
  MaterialDesc plate{"plate", glm::vec3(0.2f, 0.25f, 0.3f), glm::vec3(0.0f)};
  plate.specular = glm::vec3(0.6f, 0.5f, 0.4f);
  plate.specularExponent = 100.0f;
  s.materials = {plate, MaterialDesc{"light", glm::vec3(0.0f), glm::vec3(5.0f, 4.0f, 3.0f)}};
  addFloor(s, 0);
  addQuad(s, {-0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, {-0.5f, 1.0f, 0.5f}, 1);
  s.environment.enabled = true;
  s.environment.file = writeSky(dir);
  s.camera.position = {-1.0f, 1.0f, 0.1f};
  s.camera.target = {-0.5f, 0.0f, 0.1f};
  s.camera.fovY = 20.0f;
  s.camera.width = s.camera.height = 8;
  s.render.spp = 512;
  finishScene(s);
  const Film path = renderPath(s, 2), direct = renderDirect(s, "mis");
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": path " << imageMean(path, c) << " direct " << imageMean(direct, c));
    CHECK(std::fabs(zDiff(path, direct, c)) < 4.0);
    CHECK(pixelsApart(path, direct, c) <= 1);
  }
}

TEST_CASE("path: glossy furnace: inside a closed box of Kd = Ks = 0.3 emitting Le, Le/(1-0.3) <= L <= Le/(1-0.6)" * doctest::test_suite("opencl")) {
  // Every inner face reflects Kd (Lambert) plus at most Ks (GGX loses energy): the furnace value
  // lies between the Lambert-only and the lossless answers.
  Scene s = cubeScene(false);
  s.environment.enabled = false;
  MaterialDesc m{"box", glm::vec3(0.3f), glm::vec3(1.0f)};
  m.specular = glm::vec3(0.3f);
  m.specularExponent = 20.0f;
  s.materials = {m};
  for (SceneTriangle& t : s.triangles) std::swap(t.v[1], t.v[2]);  // front faces inward
  s.camera.position = {0.05f, 0.1f, 0.2f};
  s.camera.target = {0.05f, 0.1f, -1.0f};
  s.camera.fovY = 60.0f;
  s.render.spp = 256;
  const Film f = renderPath(s, -1);
  ImageEstimate e = imageEstimate(f, 0);
  INFO("L = " << e.mean << " +- " << e.standardError);
  CHECK(e.mean > 1.0 / 0.7 + 4.0 * e.standardError);   // the glossy lobe adds light
  CHECK(e.mean < 1.0 / 0.4 - 4.0 * e.standardError);   // but never more than Kd + Ks allows
}

}  // namespace test_file_env_glossy
