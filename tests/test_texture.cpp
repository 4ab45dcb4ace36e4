// test_texture.cpp: the host texture pipeline (host/texture: sRGB decoding, half floats, box-filtered
// mip pyramids of any size, the texture budget, loading each file once) and the pure lookups of
// kernels/shared/texture.h (bilinear, repeat wrap, v = 0 at the bottom, trilinear, footprints).
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "cli_runner.h"
#include "test_images.h"
#include "image/exr_layers.h"
#include "image/oiio_loader.h"
#include "kernels/shared/texture.h"
#include "texture/mip_chain.h"
#include "texture/scene_textures.h"
#include "texture/texture_budget.h"
#include "util/errors.h"

namespace test_file_texture {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using montecl_test::TempDir;

namespace {

using montecl_test::writeImage8;

RgbaImage randomImage(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(0.0f, 1.0f);
  RgbaImage im;
  im.width = w;
  im.height = h;
  for (int i = 0; i < w * h; ++i) im.texels.push_back(glm::vec4(d(rng), d(rng), d(rng), d(rng)));
  return im;
}

glm::dvec4 meanOf(const RgbaImage& im) {
  glm::dvec4 s(0.0);
  for (const glm::vec4& t : im.texels) s += glm::dvec4(t);
  return s / double(im.texels.size());
}

TextureTables tablesOf(const SceneTextures& st) {
  return TextureTables{st.textures.data(), st.levels.data(), st.texels.data()};
}

}  // namespace

TEST_CASE("texture: sRGB decoding and half floats" * doctest::test_suite("cpu")) {
  CHECK(srgbToLinear(128.0f / 255.0f) == doctest::Approx(0.2158605).epsilon(1e-6));
  CHECK(srgbToLinear(0.0f) == 0.0f);
  CHECK(srgbToLinear(1.0f) == doctest::Approx(1.0).epsilon(1e-6));
  CHECK(srgbToLinear(0.04f) == doctest::Approx(0.04 / 12.92));
  for (float f : {0.0f, 1.0f, -2.5f, 0.5f, 65504.0f, 6.103515625e-05f, 5.9604645e-08f})
    CHECK(halfToFloat(floatToHalf(f)) == f);  // representable: exact
  CHECK(std::isinf(halfToFloat(floatToHalf(1e6f))));
  CHECK(halfToFloat(floatToHalf(1.0f + 1.0f / 4096.0f)) == 1.0f);  // a tie rounds to even
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> d(1e-3f, 100.0f);
  for (int i = 0; i < 1000; ++i) {
    const float f = d(rng);
    CHECK(std::fabs(halfToFloat(floatToHalf(f)) - f) <= f * (1.0f / 2048.0f));  // half an ulp
  }
}

TEST_CASE("texture: mip pyramids keep the mean at every level, for any size" * doctest::test_suite("cpu")) {
  CHECK(mipLevelCount(1, 1) == 1);
  CHECK(mipLevelCount(8, 2) == 4);
  CHECK(mipLevelCount(5, 3) == 3);
  for (auto [w, h] : {std::pair{8, 8}, {5, 3}, {7, 1}, {1, 9}, {33, 17}}) {
    const RgbaImage base = randomImage(w, h, unsigned(w * 100 + h));
    const std::vector<RgbaImage> chain = buildMipChain(base);
    REQUIRE(int(chain.size()) == mipLevelCount(w, h));
    CHECK(chain.back().width == 1);
    CHECK(chain.back().height == 1);
    const glm::dvec4 m0 = meanOf(base);
    for (const RgbaImage& level : chain)
      for (int c = 0; c < 4; ++c) CHECK(meanOf(level)[c] == doctest::Approx(m0[c]).epsilon(1e-5));
  }
  // Even sizes: exactly the 2x2 box.
  const RgbaImage im = randomImage(4, 2, 9);
  const RgbaImage half = downsample(im);
  REQUIRE(half.width == 2);
  REQUIRE(half.height == 1);
  const glm::vec4 box = (im.at(2, 0) + im.at(3, 0) + im.at(2, 1) + im.at(3, 1)) * 0.25f;
  for (int c = 0; c < 4; ++c) CHECK(half.at(1, 0)[c] == doctest::Approx(box[c]));
}

TEST_CASE("texture: the budget drops the largest finest levels first and keeps the coarsest" * doctest::test_suite("cpu")) {
  const std::vector<std::vector<std::uint64_t>> bytes{{64, 16, 4, 1}, {256, 64, 16, 4, 1}, {8}};
  CHECK(finestLevelsToDrop(bytes, 1000) == std::vector<int>{0, 0, 0});
  CHECK(finestLevelsToDrop(bytes, 200) == std::vector<int>{0, 1, 0});  // 85 + 85 + 8 = 178
  CHECK(finestLevelsToDrop(bytes, 100) == std::vector<int>{1, 2, 0});  // 21 + 21 + 8 = 50
  CHECK(finestLevelsToDrop(bytes, 0) == std::vector<int>{3, 4, 0});    // never below one level
}

TEST_CASE("texture: bilinear lookups with repeat wrap, v = 0 at the bottom, trilinear by footprint" * doctest::test_suite("cpu")) {
  RgbaImage im = randomImage(8, 4, 5);
  SceneTextures st;
  std::vector<std::string> warnings;
  packTextures(st, {im}, 1ull << 30, warnings);
  CHECK(warnings.empty());
  REQUIRE(st.textures.size() == 1);
  REQUIRE(st.textures[0].levelCount == 4);
  const TextureTables tt = tablesOf(st);
  const auto h = [](float f) { return halfToFloat(floatToHalf(f)); };
  // Texel centres give the texel (as a half); row 0 is v in [0, 1/4).
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const float u = (x + 0.5f) / 8.0f, v = (y + 0.5f) / 4.0f;
      for (float shift : {0.0f, 1.0f, -3.0f}) {
        const float4 c = texture_sample(tt, 0, u + shift, v - shift, 0.0f);
        for (int k = 0; k < 4; ++k) CHECK(c[k] == h(im.at(x, y)[k]));
      }
    }
  // Half-way between columns 7 and 0 (wrap) of row 2.
  const float4 mid = texture_bilinear(tt, 0, 1.0f, 2.5f / 4.0f);
  CHECK(mid.x == doctest::Approx(0.5f * (h(im.at(7, 2).x) + h(im.at(0, 2).x))).epsilon(1e-6));
  // A footprint of the whole texture: the 1x1 level, the mean.
  const float4 coarse = texture_sample(tt, 0, 0.3f, 0.7f, 4.0f);
  CHECK(coarse.x == doctest::Approx(meanOf(im).x).epsilon(2e-3));
  // Level of detail: a footprint of one texel of level 0 (geometric mean size sqrt(32)) is lod 0,
  // twice that is lod 1, clamped at the coarsest level.
  CHECK(texture_lod(st.textures[0], 1.0f / std::sqrt(32.0f)) == doctest::Approx(0.0f).epsilon(1e-5));
  CHECK(texture_lod(st.textures[0], 2.0f / std::sqrt(32.0f)) == doctest::Approx(1.0f).epsilon(1e-5));
  CHECK(texture_lod(st.textures[0], 100.0f) == 3.0f);
  CHECK(texture_lod(st.textures[0], 0.0f) == 0.0f);
  // Footprints: cone width times the UV/position length ratio, divided by |cos|.
  CHECK(texture_footprint(0.1f, 4.0f, 1.0f, 1.0f) == doctest::Approx(0.2f));
  CHECK(texture_footprint(0.1f, 4.0f, 1.0f, -0.5f) == doctest::Approx(0.4f));
  CHECK(texture_footprint(0.1f, 0.0f, 1.0f, 1.0f) == 0.0f);
}

TEST_CASE("texture: texel indices under each wrap mode, and the identity transform reads the same bits" * doctest::test_suite("cpu")) {
  // A row of 4 texels: repeat (i mod 4), clamp (to 0 .. 3), mirrored repeat (0 1 2 3 3 2 1 0 ...).
  const int is[] = {-5, -4, -2, -1, 0, 3, 4, 5, 7, 8, 11};
  const uint repeat[] = {3, 0, 2, 3, 0, 3, 0, 1, 3, 0, 3};
  const uint clamp[] = {0, 0, 0, 0, 0, 3, 3, 3, 3, 3, 3};
  const uint mirror[] = {3, 3, 1, 0, 0, 3, 3, 2, 0, 0, 3};
  for (std::size_t k = 0; k < sizeof is / sizeof is[0]; ++k) {
    CAPTURE(is[k]);
    CHECK(texture_wrap_mode(is[k], 4u, MCL_WRAP_REPEAT) == repeat[k]);
    CHECK(texture_wrap_mode(is[k], 4u, MCL_WRAP_CLAMP) == clamp[k]);
    CHECK(texture_wrap_mode(is[k], 4u, MCL_WRAP_MIRROR) == mirror[k]);
  }
  CHECK(texture_reduce(-0.25f, MCL_WRAP_REPEAT) == 0.75f);
  CHECK(texture_reduce(-0.25f, MCL_WRAP_MIRROR) == 1.75f);
  CHECK(texture_reduce(-0.25f, MCL_WRAP_CLAMP) == 0.0f);
  CHECK(texture_reduce(1.5f, MCL_WRAP_CLAMP) == 1.0f);
  // A texture as the loader packs it (identity rows, repeat) reads exactly what the repeat lookup does.
  TextureDesc d{};
  d.uvRow0 = float4(1.0f, 0.0f, 0.0f, 0.0f);
  d.uvRow1 = float4(0.0f, 1.0f, 0.0f, 0.0f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uv(-3.0f, 3.0f);
  for (int i = 0; i < 1000; ++i) {
    const float u = uv(rng), v = uv(rng);
    const float2 t = texture_uv(d, u, v);
    REQUIRE(t.x == u);
    REQUIRE(t.y == v);
  }
  CHECK(texture_uv_scale(d) == 1.0f);
}

TEST_CASE("texture: a tiny budget keeps coarser levels and says which textures" * doctest::test_suite("cpu")) {
  SceneTextures st;
  st.files = {"big.png", "small.png"};
  std::vector<std::string> warnings;
  packTextures(st, {randomImage(64, 64, 1), randomImage(4, 4, 2)}, 8 * 1024, warnings);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("big.png 64x64 -> 16x16") != std::string::npos);
  CHECK(warnings[0].find("small.png") == std::string::npos);
  CHECK(st.bytes() <= 8 * 1024);
  CHECK(st.textures[0].dropped == 2);
  CHECK(st.levels[st.textures[0].firstLevel].width == 16);
  // The lookup skips the dropped levels: a footprint of one level-0 texel reads level 2 (kept 0).
  CHECK(texture_lod(st.textures[0], 1.0f / 64.0f) == 0.0f);
  CHECK(texture_lod(st.textures[0], 8.0f / 64.0f) == doctest::Approx(1.0f).epsilon(1e-5));
}

TEST_CASE("texture: scene textures load once per file; 8-bit decodes sRGB, alpha stays linear" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::string rgba = dir.file("leaf.png"), grey = dir.file("mask.png");
  writeImage8(rgba, 4, 2, 4, [](int x, int, int c) { return c == 3 ? (x < 2 ? 0 : 255) : 128; });
  writeImage8(grey, 2, 2, 1, [](int, int y, int) { return y == 0 ? 128 : 0; });  // top row 128
  Scene scene;
  MaterialDesc a("a", glm::vec3(1.0f));
  a.albedoTexture = rgba;
  a.alphaTexture = rgba;
  MaterialDesc b("b", glm::vec3(1.0f));
  b.albedoTexture = rgba;
  b.alphaTexture = grey;
  scene.materials = {a, b, MaterialDesc("plain", glm::vec3(0.5f))};
  std::vector<std::string> warnings;
  const SceneTextures st = loadSceneTextures(scene, kDefaultTextureBudget, warnings);
  CHECK(warnings.empty());
  REQUIRE(st.textures.size() == 2);  // leaf.png once (colour and its alpha), mask.png linear
  CHECK(st.materials[0].albedo == 0);
  CHECK(st.materials[0].alpha == 0);
  CHECK(st.materials[0].alphaChannel == 3);
  CHECK(st.materials[1].alpha == 1);
  CHECK(st.materials[1].alphaChannel == 0);
  CHECK(st.materials[2].albedo == MCL_NO_TEXTURE);
  CHECK(st.materials[2].alpha == MCL_NO_TEXTURE);
  const TextureTables tt = tablesOf(st);
  const float4 c = texture_sample(tt, 0, 0.125f, 0.25f, 0.0f);
  CHECK(c.x == doctest::Approx(0.2158605).epsilon(5e-4));  // sRGB 128, as a half
  CHECK(c.w == 0.0f);
  CHECK(texture_sample(tt, 0, 0.875f, 0.25f, 0.0f).w == 1.0f);
  // The mask's top row (v in [0.5, 1)) is 128/255 linear, its bottom row 0.
  CHECK(texture_sample(tt, 1, 0.25f, 0.75f, 0.0f).x == doctest::Approx(128.0 / 255.0).epsilon(5e-4));
  CHECK(texture_sample(tt, 1, 0.25f, 0.25f, 0.0f).x == 0.0f);
}

TEST_CASE("texture: an unreadable texture is an input error naming the file and the material" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("bad.png", "not a png");
  Scene scene;
  MaterialDesc m("wood", glm::vec3(1.0f));
  m.albedoTexture = dir.file("bad.png");
  scene.materials = {m};
  std::vector<std::string> warnings;
  try {
    loadSceneTextures(scene, kDefaultTextureBudget, warnings);
    FAIL("no error");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.rfind(dir.file("bad.png") + ": material 'wood' map_Kd: cannot read image", 0) == 0);
    CHECK(what.find('\n') == std::string::npos);
  }
}

}  // namespace test_file_texture
