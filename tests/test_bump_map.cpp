// test_bump_map.cpp: height-map bump mapping (kernels/shared/bump_map.h; the gradient texture made
// on the host, texture/bump_gradient.cpp): the gradient of ramps under each wrap mode; a plane
// whose height map is a linear ramp (slope 30 degrees) under an area light has the irradiance of
// the geometrically tilted plane (z-scores against the estimators' standard errors and against
// Lambert's form factor); a constant height map renders the unmapped image bit for bit; MTL
// bump / map_Bump / map_bump (-bm) load, norm beside bump is one warning; a -bm that is not a
// finite number, or a missing bump file, is one line naming the MTL and line, exit 2.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "render/wavefront.h"
#include "test_images.h"
#include "test_scenes.h"
#include "texture/bump_gradient.h"
#include "texture/scene_textures.h"

namespace test_file_bump_map {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
const glm::vec3 kRho(0.5f, 0.6f, 0.7f);
const glm::vec3 kLe(2.0f, 3.0f, 4.0f);

// The height map: 64 x 4 grey texels, 4 i / 255 in column i (a ramp in u; dh/du = 256 / 255 per
// unit of UV between the end columns, where the repeat wrap jumps).
void writeRamp(const std::string& path) {
  writeImage8(path, 64, 4, 1, [](int x, int, int) { return 4 * x; });
}
constexpr double kRampSlope = 256.0 / 255.0;

// u = 0.25 + x / 8, v = 0.5 - z / 8: UV extent 1/8 per world unit, so d = bm h rises by
// bm kRampSlope / 8 per unit of x.
glm::vec2 planeUv(glm::vec3 p) { return {0.25f + p.x / 8.0f, 0.5f - p.z / 8.0f}; }

// The point seen (every pixel: a tiny field of view), and the square light above it, front face down.
const glm::vec3 kAt(0.2f, 0.0f, -0.1f);
std::vector<glm::vec3> lightQuad() {
  const float y = 0.8f, x0 = -1.6f, x1 = -0.6f, z0 = -0.6f, z1 = 0.4f;
  return {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};  // cross(v1 - v0, v2 - v0) along -y
}

// A square of half-size 1 about kAt in the plane with unit normal n (through kAt), material 0
// with bump map `bump` (scale bm; none when empty), seen from 0.05 along n, lit by lightQuad();
// corners carry the normal n (smooth) when `normals`.
Scene tiltedPlane(glm::vec3 n, const std::string& bump, float bm, int spp, Integrator integrator, bool normals = false) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<bumped plane>";
  MaterialDesc m("floor", kRho, glm::vec3(0.0f));
  m.bumpTexture = bump;
  m.bumpScale = bm;
  s.materials = {m, MaterialDesc("light", glm::vec3(0.0f), kLe)};
  // The tangent along x tilted with n (n's component along z is 0), and z.
  const glm::vec3 tx = glm::normalize(glm::vec3(n.y, -n.x, 0.0f)), tz(0.0f, 0.0f, 1.0f);
  const glm::vec3 a = kAt - tx + tz, b = kAt + tx + tz, c = kAt + tx - tz, d = kAt - tx - tz;
  const auto uv = [&](glm::vec3 p) { return planeUv(p); };
  const std::uint8_t attributes = kHasUv | (normals ? kHasNormals : 0);
  s.triangles.push_back(SceneTriangle{{a, b, c}, 0, {n, n, n}, {uv(a), uv(b), uv(c)}, attributes});
  s.triangles.push_back(SceneTriangle{{a, c, d}, 0, {n, n, n}, {uv(a), uv(c), uv(d)}, attributes});
  const std::vector<glm::vec3> q = lightQuad();
  s.triangles.push_back(SceneTriangle{{q[0], q[1], q[2]}, 1});
  s.triangles.push_back(SceneTriangle{{q[0], q[2], q[3]}, 1});
  s.camera.position = kAt + n * 0.05f;
  s.camera.target = kAt;
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 0.01f;
  s.camera.width = s.camera.height = 4;
  s.render.spp = spp;
  s.render.integrator = integrator;
  s.render.directSampling = DirectSampling::Light;
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

// Lambert's point-to-polygon form factor (as test_direct.cpp).
double formFactor(const std::vector<glm::vec3>& poly, glm::dvec3 x, glm::dvec3 n) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    glm::dvec3 a = glm::normalize(glm::dvec3(poly[i]) - x), b = glm::normalize(glm::dvec3(poly[(i + 1) % poly.size()]) - x);
    sum += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
  }
  return std::fabs(sum) / (2.0 * kPi);
}

double zScore(const ImageEstimate& a, const ImageEstimate& b) {
  return (a.mean - b.mean) / std::sqrt(a.standardError * a.standardError + b.standardError * b.standardError);
}

}  // namespace

TEST_CASE("bump map: the gradient texture of ramps is their slope per unit of UV, through each wrap mode" *
          doctest::test_suite("cpu")) {
  RgbaImage h;
  h.width = 8;
  h.height = 4;
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x) {
      const float v = 0.25f * float(x) + 0.5f * float(y);  // rows bottom first: y is v
      h.texels.push_back(glm::vec4(v, v, v, 1.0f));
    }
  // Per unit of UV: 0.25 per texel x 8 texels in u, 0.5 x 4 in v; times the scale 1.5.
  const float gu = 0.25f * 8 * 1.5f, gv = 0.5f * 4 * 1.5f;
  const RgbaImage repeat = bumpGradient(h, 1.5f, MCL_WRAP_REPEAT, MCL_WRAP_REPEAT);
  const RgbaImage clamp = bumpGradient(h, 1.5f, MCL_WRAP_CLAMP, MCL_WRAP_CLAMP);
  const RgbaImage mirror = bumpGradient(h, 1.5f, MCL_WRAP_MIRROR, MCL_WRAP_MIRROR);
  for (int y = 1; y + 1 < h.height; ++y)
    for (int x = 1; x + 1 < h.width; ++x) {
      CAPTURE(x);
      CAPTURE(y);
      for (const RgbaImage* g : {&repeat, &clamp, &mirror}) {
        CHECK(g->at(x, y).x == gu);
        CHECK(g->at(x, y).y == gv);
      }
    }
  // At the edges: clamp is one-sided (the ramp's slope still), repeat sees the jump back to the
  // start, mirrored repeat the fold (half the slope).
  CHECK(clamp.at(0, 1).x == gu);
  CHECK(clamp.at(7, 1).x == gu);
  CHECK(clamp.at(3, 0).y == gv);
  CHECK(clamp.at(3, 3).y == gv);
  CHECK(repeat.at(0, 1).x == doctest::Approx((0.25f - 1.75f) * 8 / 2 * 1.5f));
  CHECK(mirror.at(0, 1).x == doctest::Approx(gu / 2));
  // A constant: zero everywhere, exactly.
  for (glm::vec4& t : h.texels) t = glm::vec4(0.3f, 0.3f, 0.3f, 1.0f);
  for (const glm::vec4& t : bumpGradient(h, 7.0f, MCL_WRAP_REPEAT, MCL_WRAP_CLAMP).texels) {
    CHECK(t.x == 0.0f);
    CHECK(t.y == 0.0f);
  }
}

TEST_CASE("bump map: a plane whose height is a 30-degree ramp is lit like the plane tilted by 30 degrees (form factor)" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeRamp(dir.file("ramp.png"));
  // dd/dx = bm kRampSlope / 8 = tan 30 degrees; the surface rises along +x, so its normal leans
  // toward -x, toward the light (centred at x = -1.1, 58 degrees from the plane's normal).
  const double slope = std::tan(kPi / 6);
  const float bm = float(slope * 8.0 / kRampSlope);
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 tilted = glm::normalize(glm::vec3(-float(slope), 1.0f, 0.0f));
  const int spp = 1024;
  const Film bumped = render(tiltedPlane(up, dir.file("ramp.png"), bm, spp, Integrator::Direct));
  Scene geometric = tiltedPlane(tilted, "", 1.0f, spp, Integrator::Direct);
  geometric.render.seed = 7;  // independent of the bumped render's numbers
  const Film reference = render(geometric);
  Scene plain = tiltedPlane(up, "", 1.0f, spp, Integrator::Direct);
  plain.render.seed = 8;
  const Film flat = render(plain);
  const double Fbump = formFactor(lightQuad(), glm::dvec3(kAt), glm::dvec3(tilted));
  const double Fflat = formFactor(lightQuad(), glm::dvec3(kAt), glm::dvec3(up));
  MESSAGE("form factor tilted " << Fbump << ", flat " << Fflat);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const ImageEstimate b = imageEstimate(bumped, c), g = imageEstimate(reference, c), f = imageEstimate(flat, c);
    const double expected = double(kRho[c]) * double(kLe[c]) * Fbump;
    INFO("bumped " << b.mean << " +- " << b.standardError << ", tilted plane " << g.mean << " +- " << g.standardError
                   << ", flat " << f.mean << " +- " << f.standardError << ", rho Le F " << expected);
    REQUIRE(b.standardError > 0.0);
    MESSAGE("channel " << c << ": z(bumped - tilted) " << zScore(b, g) << ", z(bumped - rho Le F) "
                       << (b.mean - expected) / b.standardError << ", z(flat - tilted) " << zScore(f, g));
    CHECK(std::fabs(zScore(b, g)) < 4.0);
    CHECK(std::fabs(b.mean - expected) < 4.0 * b.standardError);
    CHECK(std::fabs(g.mean - expected) < 4.0 * g.standardError);
    // The tilt is visible: the unbumped plane is far from the tilted one.
    CHECK(std::fabs(zScore(f, g)) > 50.0);
  }
}

TEST_CASE("bump map: a constant height map renders the unmapped image bit for bit (flat and smooth-shaded)" *
          doctest::test_suite("opencl")) {
  TempDir dir;
  writeImage8(dir.file("flat.png"), 16, 8, 3, [](int, int, int) { return 77; });
  const glm::vec3 n = glm::normalize(glm::vec3(0.1f, 1.0f, 0.05f));
  for (bool normals : {false, true}) {
    CAPTURE(normals);
    for (Integrator integrator : {Integrator::Direct, Integrator::Path}) {
      Scene bumped = tiltedPlane(glm::vec3(0, 1, 0), dir.file("flat.png"), 3.0f, 16, integrator, normals);
      Scene plain = tiltedPlane(glm::vec3(0, 1, 0), "", 1.0f, 16, integrator, normals);
      for (Scene* s : {&bumped, &plain}) {
        s->camera.position = glm::vec3(0.4f, 1.5f, 1.2f);  // every pixel a different point
        s->camera.fovY = 40.0f;
        s->camera.width = s->camera.height = 12;
        if (normals)
          for (SceneTriangle& t : s->triangles)
            if (t.material == 0) t.n[1] = n;  // smooth shading that differs from the geometry
      }
      const Film a = render(bumped), b = render(plain);
      CHECK(a.mean == b.mean);
      CHECK(imageMean(b, 1) > 0.0);
    }
  }
}

TEST_CASE("bump map: MTL bump, map_Bump and map_bump load with their -bm; beside norm, one warning" * doctest::test_suite("cpu")) {
  TempDir dir;
  writeRamp(dir.file("h.png"));
  writeImage8(dir.file("n.png"), 4, 4, 3, [](int, int, int c) { return c == 2 ? 255 : 128; });
  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                     "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 2/2 3/3\nusemtl c\nf 1/1 2/2 3/3\n"
                     "usemtl d\nf 1/1 2/2 3/3\nusemtl e\nf 1/1 2/2 3/3\n");
  dir.write("m.mtl", "newmtl a\nbump -bm 0.25 h.png\nnewmtl b\nmap_Bump h.png\nnewmtl c\nmap_bump -bm -2 h.png\n"
                     "newmtl d\nnorm n.png\nbump h.png\nnewmtl e\nnorm n.png\nmap_Bump -bm 3 h.png\n");
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("m.obj"), warnings);
  REQUIRE(s.materials.size() == 5);
  const float scales[5] = {0.25f, 1.0f, -2.0f, 1.0f, 3.0f};
  for (int i = 0; i < 5; ++i) {
    CAPTURE(i);
    CHECK(s.materials[i].bumpTexture == dir.file("h.png"));
    CHECK(s.materials[i].bumpScale == scales[i]);
  }
  int both = 0;
  for (const std::string& w : warnings) {
    INFO(w);
    CHECK(w.find("not used") == std::string::npos);  // bump is no longer "not used by montecl"
    if (w.find("both norm and") != std::string::npos) {
      ++both;
      CHECK(w.find("m.mtl: line 9: material 'd': both norm and bump") != std::string::npos);
      CHECK(w.find("(1 more like it; -v lists them)") != std::string::npos);
    }
  }
  CHECK(both == 1);
  // The gradient texture is loaded for a, b, c (shared by none: each scale its own), not for d, e.
  std::vector<std::string> textureWarnings;
  const SceneTextures t = loadSceneTextures(s, kDefaultTextureBudget, textureWarnings);
  REQUIRE(t.materials.size() == 5);
  for (int i = 0; i < 3; ++i) CHECK(t.materials[i].bump != MCL_NO_TEXTURE);
  CHECK(t.materials[0].bump != t.materials[1].bump);
  for (int i = 3; i < 5; ++i) {
    CHECK(t.materials[i].bump == MCL_NO_TEXTURE);
    CHECK(t.materials[i].normal != MCL_NO_TEXTURE);
  }
}

TEST_CASE("bump map: a -bm that is not a finite number, or a missing bump file, is one line naming the MTL and line, exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeRamp(dir.file("h.png"));
  dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n");
  const struct {
    const char* statement;
    std::string needle;
  } cases[] = {
      {"bump -bm nan h.png", "m.mtl: line 3: material 'a': bump -bm 'nan' must be a finite number"},
      {"map_Bump -bm 1e999 h.png", "m.mtl: line 3: material 'a': map_Bump -bm '1e999' must be a finite number"},
      {"map_bump -bm inf h.png", "m.mtl: line 3: material 'a': map_bump -bm 'inf' must be a finite number"},
      {"bump -bm x h.png", "m.mtl: line 3: material 'a': bump -bm 'x' must be a finite number"},
      {"bump gone.png", "m.mtl: line 3: material 'a': bump 'gone.png': cannot open"},
  };
  for (const auto& c : cases) {
    CAPTURE(std::string(c.statement));
    dir.write("m.mtl", std::string("newmtl a\nKd 0.5 0.5 0.5\n") + c.statement + "\n");
    const CliResult r = runMontecl({"render", dir.file("m.obj"), "-o", dir.file("out.png"), "-q"});
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(c.needle) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
  }
}

}  // namespace test_file_bump_map
