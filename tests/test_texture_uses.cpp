// test_texture_uses.cpp: a render decodes only the textures its image reads (render/integrators.h
// textureUsesOf): AO gives the same image, bit for bit, whether its albedo, emission, normal and
// metallic-roughness files are loaded (the albedo AOV asks for them), left unread or corrupt; the
// cut-out's alpha texture is still read; the albedo and normal AOVs, the denoiser's guides and the
// lit integrators still read theirs (a corrupt one is exit 2 naming it); under a tight texture
// budget the textures AO loads keep the levels they would keep with every texture loaded.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/oidn_denoiser.h"
#include "skip.h"
#include "test_images.h"

namespace test_file_texture_uses {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// A floor and, above it, a quad that wears every kind of texture: the quad's stripes cut out, so
// the AO of the floor under it depends on the alpha texture.
void writeUsesScene(const TempDir& dir) {
  dir.write("floor.obj", "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nf 1 2 3 4\n");
  dir.write("quad.obj",
            "v -0.6 -0.6 0.3\nv 0.6 -0.6 0.3\nv 0.6 0.6 0.3\nv -0.6 0.6 0.3\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "f 1/1 2/2 3/3 4/4\n");
  writeImage8(dir.file("albedo.png"), 8, 8, 3, [](int x, int y, int c) { return (x * 30 + y * 7 + c * 50) % 256; });
  writeImage8(dir.file("alpha.png"), 8, 8, 1, [](int x, int, int) { return (x / 2) % 2 ? 255 : 0; });
  writeImage8(dir.file("emission.png"), 8, 8, 3, [](int x, int y, int) { return (x + y) % 2 ? 200 : 10; });
  writeImage8(dir.file("normal.png"), 8, 8, 3, [](int x, int, int c) { return c == 2 ? 200 : c == 0 ? 60 + x * 16 : 128; });
  writeImage8(dir.file("mr.png"), 8, 8, 3, [](int x, int y, int c) { return c == 0 ? 0 : (x * 20 + y * 10) % 256; });
  dir.write("scene.json",
            R"({"camera": {"position": [0.4, -1.2, 2.2], "target": [0, 0, 0], "up": [0, 0, 1], "fov_y": 50,
                "width": 16, "height": 12},
                "meshes": [{"file": "floor.obj"},
                           {"file": "quad.obj", "material": {"type": "metal_rough", "albedo_texture": "albedo.png",
                            "alpha_texture": "alpha.png", "emission": [1, 1, 1], "emission_texture": "emission.png",
                            "normal_texture": "normal.png", "metallic_roughness_texture": "mr.png"}}],
                "render": {"integrator": "ao", "spp": 4, "seed": 3, "ao_distance": 1.0, "background": [0.2, 0.3, 0.4]}})");
}

std::vector<std::string> renderArgs(const TempDir& dir, const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> a = {"render", dir.file("scene.json"), "-o", dir.file(out), "-q", "--overwrite"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

// The planes of a and b named names are equal bit for bit.
bool samePlanes(const LayeredImage& a, const LayeredImage& b, const std::vector<std::string>& names) {
  for (const std::string& n : names) {
    const std::vector<float>* pa = a.find(n);
    const std::vector<float>* pb = b.find(n);
    if (!pa || !pb || *pa != *pb) return false;
  }
  return true;
}

const std::vector<std::string> kRenderPlanes = {"R", "G", "B", "samples", "var.R", "var.G", "var.B"};

}  // namespace

TEST_CASE("texture uses: AO reads only the cut-out's alpha texture; the same image whatever the others hold" *
          doctest::test_suite("cli")) {
  TempDir dir;
  writeUsesScene(dir);
  // With the albedo AOV every texture is loaded; without, only the alpha texture: the AO is the same.
  const CliResult loaded = runMontecl(renderArgs(dir, "loaded.exr", {"--aov", "albedo"}));
  REQUIRE(loaded.exitCode == 0);
  const CliResult plain = runMontecl(renderArgs(dir, "plain.exr", {}));
  REQUIRE(plain.exitCode == 0);
  const LayeredImage a = readLayeredImage(dir.file("loaded.exr"));
  const LayeredImage b = readLayeredImage(dir.file("plain.exr"));
  CHECK(samePlanes(a, b, kRenderPlanes));
  // The albedo AOV read the texture: the quad's albedo is not one colour.
  const std::vector<float>& albedoR = *a.find("albedo.R");
  CHECK(std::count_if(albedoR.begin(), albedoR.end(), [&](float v) { return v != albedoR[0]; }) > 0);
  // The others corrupt: AO neither reads them nor changes.
  for (const char* f : {"albedo.png", "emission.png", "normal.png", "mr.png"}) dir.write(f, "not an image");
  const CliResult corrupt = runMontecl(renderArgs(dir, "corrupt.exr", {}));
  REQUIRE(corrupt.exitCode == 0);
  CHECK(corrupt.err.empty());
  const LayeredImage c = readLayeredImage(dir.file("corrupt.exr"));
  CHECK(samePlanes(b, c, kRenderPlanes));
  // The alpha texture is read by AO: corrupt, it is exit 2 naming it.
  dir.write("alpha.png", "not an image");
  const CliResult badAlpha = runMontecl(renderArgs(dir, "alpha.exr", {}));
  CHECK(badAlpha.exitCode == 2);
  CHECK(badAlpha.err.find("alpha.png: material") != std::string::npos);
  CHECK(!std::filesystem::exists(dir.file("alpha.exr")));
}

TEST_CASE("texture uses: the albedo and normal AOVs and the lit integrators read their textures" *
          doctest::test_suite("cli")) {
  TempDir dir;
  writeUsesScene(dir);
  const auto failsNaming = [&](const std::vector<std::string>& extra, const std::string& file) {
    const CliResult r = runMontecl(renderArgs(dir, "out.exr", extra));
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(file + ": material") != std::string::npos);
    CHECK(!std::filesystem::exists(dir.file("out.exr")));
  };
  dir.write("albedo.png", "not an image");
  failsNaming({"--aov", "albedo"}, "albedo.png");
  failsNaming({"--integrator", "direct"}, "albedo.png");
  writeUsesScene(dir);
  dir.write("normal.png", "not an image");
  failsNaming({"--aov", "normal"}, "normal.png");
  writeUsesScene(dir);
  dir.write("emission.png", "not an image");
  failsNaming({"--integrator", "path"}, "emission.png");
  writeUsesScene(dir);
  dir.write("mr.png", "not an image");
  failsNaming({"--aov", "depth"}, "mr.png");  // a film with AOVs records the albedo too
}

TEST_CASE("texture uses: --denoise under AO reads the albedo textures for its guide" * doctest::test_suite("cli")) {
  MCL_SKIP_UNLESS(oidnProblem().empty(), oidnProblem());
  TempDir dir;
  writeUsesScene(dir);
  dir.write("albedo.png", "not an image");
  const CliResult r = runMontecl(renderArgs(dir, "out.exr", {"--denoise"}));
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("albedo.png: material") != std::string::npos);
}

TEST_CASE("texture uses: under a tight --texture-budget AO keeps the levels it would have with every texture loaded" *
          doctest::test_suite("cli")) {
  // The budget drops finest levels over all the scene's textures: the alpha texture loses its
  // finest level to the albedo texture's share, whether or not the albedo texture is decoded.
  TempDir dir;
  writeUsesScene(dir);
  writeImage8(dir.file("albedo.png"), 8, 8, 3, [](int x, int y, int c) { return ((x + y) % 2) * 200 + c; });
  writeImage8(dir.file("alpha.png"), 8, 8, 1, [](int x, int, int) { return x % 2 ? 255 : 0; });
  dir.write("scene.json",
            R"({"camera": {"position": [0.2, -0.6, 1.4], "target": [0, 0, 0.3], "up": [0, 0, 1], "fov_y": 50,
                "width": 32, "height": 24},
                "meshes": [{"file": "floor.obj"},
                           {"file": "quad.obj", "material": {"albedo_texture": "albedo.png", "alpha_texture": "alpha.png"}}],
                "render": {"integrator": "ao", "spp": 4, "seed": 3, "ao_distance": 1.0, "background": [0.2, 0.3, 0.4]}})");
  const std::vector<std::string> tight = {"--texture-budget", "0.0007"};  // 734 bytes: both 8x8 textures lose level 0
  std::vector<std::string> all = tight;
  all.insert(all.end(), {"--aov", "albedo"});
  const CliResult loaded = runMontecl(renderArgs(dir, "loaded.exr", all));
  REQUIRE(loaded.exitCode == 0);
  CHECK(loaded.err.find("alpha.png 8x8 -> 4x4") != std::string::npos);
  const CliResult plain = runMontecl(renderArgs(dir, "plain.exr", tight));
  REQUIRE(plain.exitCode == 0);
  const CliResult full = runMontecl(renderArgs(dir, "full.exr", {}));
  REQUIRE(full.exitCode == 0);
  const LayeredImage a = readLayeredImage(dir.file("loaded.exr"));
  const LayeredImage b = readLayeredImage(dir.file("plain.exr"));
  const LayeredImage c = readLayeredImage(dir.file("full.exr"));
  CHECK(samePlanes(a, b, kRenderPlanes));
  CHECK(!samePlanes(b, c, kRenderPlanes));  // the dropped level shows: the budget did change the image
}

TEST_CASE("texture uses: one file as colour and as cut-out (no alpha channel): AO's image with or without the colour" *
          doctest::test_suite("cli")) {
  // Such a file is two textures (sRGB colour, linear alpha from its first channel); AO decodes it
  // for the alpha one only and must pick that one, with the budget's levels of both.
  TempDir dir;
  writeUsesScene(dir);
  dir.write("quad.obj",
            "mtllib quad.mtl\nv -0.6 -0.6 0.3\nv 0.6 -0.6 0.3\nv 0.6 0.6 0.3\nv -0.6 0.6 0.3\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "usemtl m\nf 1/1 2/2 3/3 4/4\n");
  dir.write("quad.mtl", "newmtl m\nKd 1 1 1\nmap_Kd both.png\nmap_d both.png\n");
  writeImage8(dir.file("both.png"), 8, 8, 3, [](int x, int y, int) { return x % 2 ? 255 : y * 30; });
  dir.write("scene.json",
            R"({"camera": {"position": [0.2, -0.6, 1.4], "target": [0, 0, 0.3], "up": [0, 0, 1], "fov_y": 50,
                "width": 32, "height": 24},
                "meshes": [{"file": "floor.obj"}, {"file": "quad.obj"}],
                "render": {"integrator": "ao", "spp": 4, "seed": 3, "ao_distance": 1.0, "background": [0.2, 0.3, 0.4]}})");
  for (const char* budget : {"1024", "0.0007"}) {
    CAPTURE(budget);
    const CliResult loaded = runMontecl(renderArgs(dir, "loaded.exr", {"--texture-budget", budget, "--aov", "albedo"}));
    REQUIRE(loaded.exitCode == 0);
    const CliResult plain = runMontecl(renderArgs(dir, "plain.exr", {"--texture-budget", budget}));
    REQUIRE(plain.exitCode == 0);
    CHECK(samePlanes(readLayeredImage(dir.file("loaded.exr")), readLayeredImage(dir.file("plain.exr")), kRenderPlanes));
  }
}

}  // namespace test_file_texture_uses
