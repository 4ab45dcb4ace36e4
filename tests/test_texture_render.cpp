// test_texture_render.cpp: textures and cut-outs through the kernels (the default OpenCL device):
// a textured quad's albedo AOV is the sRGB-decoded texel; a grazing checkerboard at 1 spp has a
// far field close to the checker mean (mip-mapped ray-cone lookups, no moire); a fully
// transparent cut-out neither occludes (AO exactly 1) nor shows; a striped cut-out passes half of
// the AO rays (z-test); a tiny texture budget renders with coarser levels; through the command
// line (OBJ + MTL map_Kd): one warning over --texture-budget, and a bad texture file is exit 2 where an image reads it (AO loads no colour texture),
// one line, no output file.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "test_images.h"
#include "image/exr_layers.h"
#include "image/oiio_loader.h"
#include "render/wavefront.h"
#include "test_scenes.h"
#include "texture/mip_chain.h"
#include "texture/scene_textures.h"

namespace test_file_texture_render {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

using montecl_test::writeImage8;

Film render(const Scene& s, RenderOptions o, const SceneTextures* textures = nullptr, bool host = false) {
  static const DeviceInfo defaultDevice = selectDevice("");
  const DeviceInfo device = host ? hostDeviceInfo() : defaultDevice;
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(device, o);
  RenderStats stats;
  RenderPart part;
  part.textures = textures;
  return r.render(s, bvh, stats, {}, part);
}

// The quad a, b, c, d (counter-clockwise from its front) with texture coordinates ta .. td.
void addUvQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec2 ta, glm::vec2 tb,
               glm::vec2 tc, glm::vec2 td, std::uint32_t material) {
  SceneTriangle t1{{a, b, c}, material, {}, {ta, tb, tc}, kHasUv};
  SceneTriangle t2{{a, c, d}, material, {}, {ta, tc, td}, kHasUv};
  s.triangles.push_back(t1);
  s.triangles.push_back(t2);
}

// 8-bit value of logical texel (i, j) (j = 0 the bottom row) of the textured-quad test.
int texelValue(int i, int j, int c) { return (37 * i + 71 * j + 53 * c + 128) % 256; }

}  // namespace

TEST_CASE("textures: a textured quad's albedo AOV is the linear value of each texel" * doctest::test_suite("opencl")) {
  TempDir dir;
  // 4 x 4 logical texels of 8 x 8 image texels each; texel (0, 0) of the bottom row is sRGB 128.
  writeImage8(dir.file("quad.png"), 32, 32, 3, [](int x, int y, int c) { return texelValue(x / 8, 3 - y / 8, c); });
  Scene s;
  s.path = "<textured quad>";
  MaterialDesc m("tex", glm::vec3(1.0f));
  m.albedoTexture = dir.file("quad.png");
  s.materials = {m};
  addUvQuad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0}, {1, 0}, {1, 1}, {0, 1}, 0);
  s.camera.position = {0, 0, 2};
  s.camera.target = {0, 0, 0};
  s.camera.fovY = float(glm::degrees(2.0 * std::atan(0.5)));  // the quad fills the image
  s.camera.width = s.camera.height = 64;  // half a texel per pixel: level 0
  s.render.spp = 2;
  finishScene(s);
  RenderOptions o;
  o.aovs = true;
  const Film f = render(s, o);
  int checked = 0;
  for (int py = 0; py < 64; ++py)
    for (int px = 0; px < 64; ++px) {
      if (px % 16 < 2 || px % 16 > 13 || py % 16 < 2 || py % 16 > 13) continue;  // near texel edges
      const int i = px / 16, j = 3 - py / 16;
      const std::size_t p = std::size_t(py) * 64 + px;
      for (int c = 0; c < 3; ++c) {
        const float want = srgbToLinear(float(texelValue(i, j, c)) / 255.0f);
        const float got = f.aovSum[MCL_AOV_VECTORS * p][c] / float(f.count[p]);
        REQUIRE(got == doctest::Approx(want).epsilon(1e-3));  // a half float: 2^-11 relative
        ++checked;
      }
    }
  CHECK(checked == 16 * 12 * 12 * 3);
  // sRGB 128 -> 0.2158 (texel (0, 0) red is 128).
  CHECK(f.aovSum[MCL_AOV_VECTORS * (62 * 64 + 8)].x / float(f.count[62 * 64 + 8]) == doctest::Approx(0.2158).epsilon(1e-3));
}

TEST_CASE("textures: a grazing checkerboard at 1 spp has a far field close to the checker mean" * doctest::test_suite("opencl")) {
  TempDir dir;
  writeImage8(dir.file("checker.png"), 64, 64, 3, [](int x, int y, int) { return ((x / 8 + y / 8) % 2) * 255; });
  Scene s;
  s.path = "<checker floor>";
  MaterialDesc m("checker", glm::vec3(1.0f));
  m.albedoTexture = dir.file("checker.png");
  s.materials = {m};
  const float r = 200.0f, k = 1.0f / 8.0f;  // 1-unit squares
  addUvQuad(s, {-r, 0, r}, {r, 0, r}, {r, 0, -r}, {-r, 0, -r}, {-r * k, -r * k}, {r * k, -r * k}, {r * k, r * k},
            {-r * k, r * k}, 0);
  s.camera.position = {0.3f, 1.0f, 0.2f};
  s.camera.target = {0.3f, 0.6f, -10.0f};
  s.camera.fovY = 40.0f;
  s.camera.width = 96;
  s.camera.height = 64;
  s.render.spp = 1;
  finishScene(s);
  RenderOptions o;
  o.aovs = true;
  const Film f = render(s, o);
  double farSum = 0.0, farSq = 0.0, nearSq = 0.0, nearSum = 0.0;
  int farN = 0, nearN = 0;
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    const float depth = f.aovSum[MCL_AOV_VECTORS * p].w, albedo = f.aovSum[MCL_AOV_VECTORS * p].x;
    if (depth > 15.0f && depth < 150.0f) {  // lod >= 4: levels of grey 0.5
      farSum += albedo;
      farSq += double(albedo) * albedo;
      ++farN;
    } else if (depth > 0.0f && depth < 4.0f) {
      nearSum += albedo;
      nearSq += double(albedo) * albedo;
      ++nearN;
    }
  }
  REQUIRE(farN > 300);
  REQUIRE(nearN > 300);
  const double farMean = farSum / farN, farStd = std::sqrt(std::max(0.0, farSq / farN - farMean * farMean));
  const double nearMean = nearSum / nearN, nearStd = std::sqrt(std::max(0.0, nearSq / nearN - nearMean * nearMean));
  MESSAGE("far field: mean " << farMean << ", std " << farStd << " (" << farN << " pixels); near: mean " << nearMean
                             << ", std " << nearStd);
  CHECK(farMean == doctest::Approx(0.5).epsilon(0.05));
  CHECK(farStd < 0.1);   // point sampling: about 0.5 (each pixel black or white)
  CHECK(nearStd > 0.3);  // the near squares are resolved (the texture is there)
}

TEST_CASE("cut-outs: a fully transparent quad neither occludes (AO exactly 1) nor shows" * doctest::test_suite("opencl")) {
  TempDir dir;
  writeImage8(dir.file("clear.png"), 4, 4, 4, [](int, int, int c) { return c == 3 ? 0 : 200; });
  Scene s;
  s.path = "<cut-out above a floor>";
  s.materials = {MaterialDesc("floor", glm::vec3(0.25f)), MaterialDesc("leaf", glm::vec3(1.0f))};
  s.materials[1].albedoTexture = s.materials[1].alphaTexture = dir.file("clear.png");
  addFloor(s, 0);
  addUvQuad(s, {-50, 0.5f, 50}, {50, 0.5f, 50}, {50, 0.5f, -50}, {-50, 0.5f, -50}, {0, 0}, {3, 0}, {3, 3}, {0, 3}, 1);
  s.camera.position = {0.2f, 2.0f, 0.1f};
  s.camera.target = {0.2f, 0.0f, 0.1f};
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 40.0f;
  s.camera.width = s.camera.height = 16;
  s.render.spp = 8;
  finishScene(s);
  RenderOptions o;
  o.aovs = true;
  const Film f = render(s, o);
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    REQUIRE(f.meanOf(p, 0) == 1.0);  // every AO ray escapes: exactly 1
    const float n = float(f.count[p]);
    REQUIRE(f.aovSum[MCL_AOV_VECTORS * p].x / n == 0.25f);        // the camera sees the floor's albedo
    REQUIRE(f.aovSum[MCL_AOV_VECTORS * p].w / n > 1.99f);         // at the floor's depth, not the quad's (1.5)
  }
}

TEST_CASE("cut-outs: a striped cut-out lets half of the AO rays through" * doctest::test_suite("opencl")) {
  TempDir dir;
  // Alpha stripes 4 texels wide: 0, 1, 0, 1, ... (bilinear crosses 0.5 at the stripe edges).
  writeImage8(dir.file("stripes.png"), 64, 2, 4, [](int x, int, int c) { return c == 3 ? ((x / 4) % 2) * 255 : 255; });
  Scene s;
  s.path = "<striped cut-out>";
  s.materials = {MaterialDesc("floor", glm::vec3(0.5f)), MaterialDesc("stripes", glm::vec3(1.0f))};
  s.materials[1].alphaTexture = dir.file("stripes.png");
  addFloor(s, 0);
  const float r = 100.0f, k = 4.0f;  // 32 stripe pairs per unit
  addUvQuad(s, {-r, 1, r}, {r, 1, r}, {r, 1, -r}, {-r, 1, -r}, {-r * k, 0}, {r * k, 0}, {r * k, 1}, {-r * k, 1}, 1);
  s.camera.position = {0.1f, 0.5f, 0.2f};
  s.camera.target = {0.1f, 0.0f, 0.2f};
  s.camera.up = {0, 0, -1};
  s.camera.fovY = 60.0f;
  s.camera.width = s.camera.height = 32;
  s.render.spp = 16;
  finishScene(s);
  const Film f = render(s, {});
  double sum = 0.0, n = 0.0;
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    sum += f.meanOf(p, 0) * double(f.count[p]);
    n += double(f.count[p]);
  }
  // Each AO sample is 1 (passes) or 0 (blocked): Bernoulli(1/2), up to the rays that pass
  // beyond the quad's edges (a 1e-4 fraction).
  const double mean = sum / n, se = std::sqrt(0.25 / n);
  const double z = (mean - 0.5) / se;
  MESSAGE("passed fraction " << mean << " over " << n << " AO rays, z = " << z);
  CHECK(std::fabs(z) < 4.0);
}

TEST_CASE("textures: a textured cut-out renders bit-identically on the host backend and for any wave size" * doctest::test_suite("opencl")) {
  TempDir dir;
  writeImage8(dir.file("leaf.png"), 16, 8, 4, [](int x, int y, int c) { return c == 3 ? ((x + y) % 3 ? 255 : 0) : 40 * c + 7 * x; });
  Scene s;
  s.path = "<cut-out leaf>";
  s.materials = {MaterialDesc("floor", glm::vec3(0.5f)), MaterialDesc("leaf", glm::vec3(0.9f, 0.8f, 0.7f))};
  s.materials[1].albedoTexture = s.materials[1].alphaTexture = dir.file("leaf.png");
  addFloor(s, 0);
  addUvQuad(s, {-1, 0.3f, 1}, {1, 0.3f, 1}, {1, 0.6f, -1}, {-1, 0.6f, -1}, {0, 0}, {2, 0}, {2, 1}, {0, 1}, 1);
  s.camera.position = {0.2f, 2.0f, 1.5f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = 50.0f;
  s.camera.width = s.camera.height = 12;
  s.render.spp = 4;
  finishScene(s);
  RenderOptions o;
  o.aovs = true;
  const Film cl = render(s, o);
  const Film host = render(s, o, nullptr, true);
  o.waveSize = 37;
  const Film small = render(s, o);
  CHECK(cl.mean == host.mean);
  CHECK(cl.aovSum == host.aovSum);
  CHECK(cl.mean == small.mean);
  CHECK(cl.aovSum == small.aovSum);
}

TEST_CASE("textures: a tiny budget drops fine levels with a warning and the render still works" * doctest::test_suite("opencl")) {
  TempDir dir;
  writeImage8(dir.file("big.png"), 256, 256, 3, [](int x, int y, int c) { return (x + 2 * y + 3 * c) % 256; });
  Scene s = floorScene({0, 0, 0}, 2.0f, 40.0f, 16, 2);
  s.materials[0].albedoTexture = dir.file("big.png");
  for (SceneTriangle& t : s.triangles) {
    for (int k = 0; k < 3; ++k) t.uv[k] = glm::vec2(t.v[k].x, t.v[k].z) * 0.1f;
    t.attributes = kHasUv;
  }
  std::vector<std::string> warnings;
  // 600 KiB: the finest level (512 KiB of half RGBA) fits, so the file is read (a larger one is
  // refused from its header), but the chain (683 KiB) does not.
  const SceneTextures small = loadSceneTextures(s, 600 * 1024, warnings);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("big.png 256x256 -> 128x128") != std::string::npos);
  CHECK(small.bytes() <= 600 * 1024);
  RenderOptions o;
  o.aovs = true;
  const Film f = render(s, o, &small);
  for (std::size_t p = 0; p < f.pixelCount(); ++p) {
    const float a = f.aovSum[MCL_AOV_VECTORS * p].x / float(f.count[p]);
    REQUIRE(std::isfinite(a));
    REQUIRE(a >= 0.0f);
    REQUIRE(a <= 1.0f);
  }
}

TEST_CASE("textures: montecl render warns once over --texture-budget; a bad texture file is exit 2, one line, where read" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("quad.obj",
            "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "usemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  dir.write("quad.mtl", "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n");
  writeImage8(dir.file("tex.png"), 64, 64, 3, [](int x, int y, int c) { return (x * 4 + y + c) % 256; });
  const std::vector<std::string> args = {"render", dir.file("quad.obj"), "-o", dir.file("out.png"), "--width", "16",
                                         "--height", "16", "--spp", "1", "-q", "--overwrite", "--integrator"};
  std::vector<std::string> lit = args, ao = args;
  lit.push_back("direct");  // reads the albedo texture
  ao.push_back("ao");       // reads none
  std::vector<std::string> tiny = lit;
  // 64x64 half RGBA is 32 KiB (under the budget, which refuses a larger finest level), its chain
  // 43 KiB (over it): the finest level is dropped.
  tiny.insert(tiny.end(), {"--texture-budget", "0.035"});
  const CliResult small = runMontecl(tiny);
  CHECK(small.exitCode == 0);
  CHECK(small.err.find("texture budget") != std::string::npos);
  CHECK(small.err.find("tex.png 64x64 -> 32x32") != std::string::npos);
  const CliResult full = runMontecl(lit);
  CHECK(full.exitCode == 0);
  CHECK(full.err.find("texture budget") == std::string::npos);
  std::filesystem::remove(dir.file("out.png"));
  dir.write("tex.png", "this is not a PNG");
  // AO reads no colour texture (nor loads one); the direct integrator does.
  const CliResult aoRun = runMontecl(ao);
  CHECK(aoRun.exitCode == 0);
  CHECK(aoRun.err.find("tex.png") == std::string::npos);
  std::filesystem::remove(dir.file("out.png"));
  const CliResult bad = runMontecl(lit);
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("tex.png: material 'm' map_Kd: cannot read image") != std::string::npos);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
}

}  // namespace test_file_texture_render
