// texel_codes.cpp: the code tables and the 8-bit encoder of texel levels (texture/texel_codes.h).
#include "texture/texel_codes.h"

#include <array>

#include "texture/mip_chain.h"
#include "texture/scene_textures.h"

namespace montecl {

const std::vector<std::uint16_t>& texelCodeTables() {
  static const std::vector<std::uint16_t> tables = [] {
    std::vector<std::uint16_t> t(MCL_TEXEL_TABLES);
    for (int c = 0; c < 256; ++c) {
      t[std::size_t(c)] = floatToHalf(srgbToLinear(float(c) / 255.0f));
      t[std::size_t(256 + c)] = floatToHalf(float(c) / 255.0f);
    }
    return t;
  }();
  return tables;
}

namespace {

// For each half value, the code whose table entry it is (the lowest such code), or -1.
using Reverse = std::array<std::int16_t, 65536>;
const Reverse& reverseTable(bool srgb) {
  static const auto build = [](int base) {
    Reverse r;
    r.fill(-1);
    const std::vector<std::uint16_t>& t = texelCodeTables();
    for (int c = 255; c >= 0; --c) r[t[std::size_t(base + c)]] = std::int16_t(c);
    return r;
  };
  static const Reverse s = build(0), l = build(256);
  return srgb ? s : l;
}

bool encodeWith(const std::vector<std::uint16_t>& half, bool srgb, std::vector<std::uint16_t>* codes) {
  const Reverse& rgb = reverseTable(srgb);
  const Reverse& alpha = reverseTable(false);
  codes->resize(half.size() / 2);
  for (std::size_t i = 0, o = 0; i + 3 < half.size(); i += 4, o += 2) {
    const int r = rgb[half[i]], g = rgb[half[i + 1]], b = rgb[half[i + 2]], a = alpha[half[i + 3]];
    if ((r | g | b | a) < 0) return false;
    (*codes)[o] = std::uint16_t(r | (g << 8));
    (*codes)[o + 1] = std::uint16_t(b | (a << 8));
  }
  return true;
}

}  // namespace

std::uint32_t encodeTexelCodes(const std::vector<std::uint16_t>& half, std::vector<std::uint16_t>* codes) {
  if (encodeWith(half, true, codes)) return MCL_TEXELS_SRGB8;
  if (encodeWith(half, false, codes)) return MCL_TEXELS_LINEAR8;
  codes->clear();
  codes->shrink_to_fit();
  return MCL_TEXELS_HALF;
}

}  // namespace montecl
