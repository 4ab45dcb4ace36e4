// texture_tables.cpp: the small table helpers of scene_textures.h: which materials cut out, their
// texture indices written into the device materials, the triangles flagged for the alpha test, and
// float <-> half as the device reads texels.
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "texture/scene_textures.h"

namespace montecl {

bool SceneTextures::anyAlpha() const {
  for (const MaterialTextures& m : materials)
    if (m.alpha != MCL_NO_TEXTURE) return true;
  return false;
}

std::uint16_t floatToHalf(float f) {
  std::uint32_t x;
  std::memcpy(&x, &f, 4);
  const std::uint16_t sign = std::uint16_t((x >> 16) & 0x8000u);
  const std::uint32_t a = x & 0x7fffffffu;
  if (a >= 0x7f800000u) return sign | (a > 0x7f800000u ? 0x7e00u : 0x7c00u);  // NaN, inf
  if (a >= 0x477ff000u) return sign | 0x7c00u;                                // rounds past 65504
  if (a < 0x38800000u) {  // below 2^-14: a subnormal half (nearest even by the rounding mode)
    float mag;
    std::memcpy(&mag, &a, 4);
    return sign | std::uint16_t(std::lrint(double(mag) * 16777216.0));
  }
  const std::uint32_t e = a - 0x38000000u;  // exponent bias 127 -> 15
  return sign | std::uint16_t((e + 0xfffu + ((e >> 13) & 1u)) >> 13);
}

float halfToFloat(std::uint16_t h) { return mcl_half_to_float(h); }

bool materialAlphaTested(const std::vector<MaterialDesc>& materials, const SceneTextures* textures, std::size_t i) {
  if (textures && i < textures->materials.size() && textures->materials[i].alpha != MCL_NO_TEXTURE) return true;
  return i < materials.size() && materials[i].alphaBlend && !(materials[i].alphaFactor >= 1.0f);
}

bool anyAlphaTested(const std::vector<MaterialDesc>& materials, const SceneTextures* textures) {
  const std::size_t n = std::max(materials.size(), textures ? textures->materials.size() : std::size_t(0));
  for (std::size_t i = 0; i < n; ++i)
    if (materialAlphaTested(materials, textures, i)) return true;
  return false;
}

std::vector<Triangle> alphaFlaggedTriangles(const std::vector<Triangle>& tris, const std::vector<MaterialDesc>& materials,
                                            const SceneTextures* textures) {
  if (!anyAlphaTested(materials, textures)) return {};
  std::vector<Triangle> out = tris;
  for (Triangle& t : out) {
    const std::uint32_t m = glm::floatBitsToUint(t.v0.w);
    if (materialAlphaTested(materials, textures, m))
      t.e2.w = glm::uintBitsToFloat(glm::floatBitsToUint(t.e2.w) | MCL_ATTR_ALPHA);
  }
  return out;
}

void setTextureIndices(std::vector<Material>& materials, const SceneTextures& textures) {
  for (std::size_t i = 0; i < materials.size() && i < textures.materials.size(); ++i) {
    const MaterialTextures& t = textures.materials[i];
    materials[i].albedo.w = glm::uintBitsToFloat(t.albedo);
    materials[i].alpha.x = glm::uintBitsToFloat(t.alpha);
    materials[i].alpha.z = glm::uintBitsToFloat(t.alphaChannel);
    materials[i].maps.x = glm::uintBitsToFloat(t.emission);
    materials[i].maps.y = glm::uintBitsToFloat(t.metallicRoughness);
    // One more than the index, 0 none: a zeroed Material (hand-made in tests) has no normal map.
    materials[i].maps.z = glm::uintBitsToFloat(t.normal == MCL_NO_TEXTURE ? 0u : t.normal + 1u);
    materials[i].maps.w = glm::uintBitsToFloat(t.bump == MCL_NO_TEXTURE ? 0u : t.bump + 1u);  // the same rule
    // metal_rough's transmission texture, one more than the index, in params1.w (transmission_mix.h;
    // only a transmissive metal_rough material has one, and no other kind's params1.w is touched).
    if (t.transmission != MCL_NO_TEXTURE) materials[i].params1.w = glm::uintBitsToFloat(t.transmission + 1u);
  }
}

}  // namespace montecl
