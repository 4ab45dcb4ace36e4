// test_texel_codes.cpp: 8-bit texel storage (host/texture/texel_codes.h, kernels/shared/texture.h
// texel_fetch): a finest level whose half texels are all 8-bit codes' decodes is stored in 4 bytes
// a texel and reads back every half bit for bit; any other level stays half.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "kernels/shared/texture.h"
#include "texture/mip_chain.h"
#include "texture/scene_textures.h"
#include "texture/texel_codes.h"

namespace test_file_texel_codes {  // keeps this file's helpers apart in a unity batch

using namespace montecl;

namespace {

// A w x h image of random 8-bit codes as the image reader decodes them: rgb through the sRGB
// table (srgb) or c / 255, alpha c / 255.
RgbaImage codeImage(int w, int h, bool srgb, unsigned seed) {
  std::mt19937 rng(seed);
  RgbaImage im;
  im.width = w;
  im.height = h;
  for (int i = 0; i < w * h; ++i) {
    glm::vec4 t;
    for (int c = 0; c < 4; ++c) {
      const float code = float(rng() % 256u) / 255.0f;
      t[c] = srgb && c < 3 ? srgbToLinear(code) : code;
    }
    im.texels.push_back(t);
  }
  return im;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every texel of every kept level read through texel_at against the half of the image's value
// (level 0) or stored as half (the others: the mips are averages, never codes).
void checkLevel0(const RgbaImage& im, std::uint32_t wantFormat) {
  SceneTextures st;
  std::vector<std::string> warnings;
  packTextures(st, {im}, kDefaultTextureBudget, warnings);
  REQUIRE(st.levels.size() > 1);
  CHECK(st.levels[0].format == wantFormat);
  for (std::size_t k = 1; k < st.levels.size(); ++k) CHECK(st.levels[k].format == MCL_TEXELS_HALF);
  const TextureTables tt{st.textures.data(), st.levels.data(), st.texels.data()};
  int wrong = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const float4 got = texel_at(tt, st.levels[0], std::uint32_t(x), std::uint32_t(y));
      const glm::vec4 want = im.texels[std::size_t(y) * im.width + x];
      for (int c = 0; c < 4; ++c) wrong += !sameBits(got[c], halfToFloat(floatToHalf(want[c])));
    }
  CHECK(wrong == 0);
  // Level 0's ushorts in the buffer (to level 1's start, rounded up to a half texel): 2 a texel as
  // codes, 4 as half.
  const std::uint64_t texels = std::uint64_t(im.width) * im.height;
  const std::uint64_t unit0 = wantFormat == MCL_TEXELS_HALF ? 4u : 2u;
  const std::uint64_t span = 4ull * st.levels[1].offset - unit0 * st.levels[0].offset;
  CHECK(span >= unit0 * texels);
  CHECK(span < unit0 * texels + 4);
}

}  // namespace

TEST_CASE("texel codes: 8-bit sRGB and linear finest levels stored as codes read back every half bit" *
          doctest::test_suite("cpu")) {
  checkLevel0(codeImage(37, 23, true, 1), MCL_TEXELS_SRGB8);
  checkLevel0(codeImage(16, 9, false, 2), MCL_TEXELS_LINEAR8);
  // One value that is no code's decode keeps the whole level half.
  RgbaImage odd = codeImage(8, 8, true, 3);
  odd.texels[27].y = 0.3333f;
  checkLevel0(odd, MCL_TEXELS_HALF);
  RgbaImage negative = codeImage(8, 8, false, 4);
  negative.texels[5].x = -0.25f;  // a decoded normal map's sign
  checkLevel0(negative, MCL_TEXELS_HALF);
}

TEST_CASE("texel codes: the tables hold each code's decode as the image reader makes it, as a half" *
          doctest::test_suite("cpu")) {
  const std::vector<std::uint16_t>& t = texelCodeTables();
  REQUIRE(t.size() == MCL_TEXEL_TABLES);
  for (int c = 0; c < 256; ++c) {
    CAPTURE(c);
    CHECK(t[std::size_t(c)] == floatToHalf(srgbToLinear(float(c) / 255.0f)));
    CHECK(t[std::size_t(256 + c)] == floatToHalf(float(c) / 255.0f));
  }
  std::vector<std::uint16_t> codes;
  // Codes 0 and 255 in every channel, in both orders: r | g << 8, b | a << 8.
  const std::vector<std::uint16_t> half = {t[0], t[255], t[0], t[256 + 255], t[255], t[0], t[255], t[256]};
  CHECK(encodeTexelCodes(half, &codes) == MCL_TEXELS_SRGB8);
  CHECK(codes == std::vector<std::uint16_t>{0xff00u, 0xff00u, 0x00ffu, 0x00ffu});
}

}  // namespace test_file_texel_codes
