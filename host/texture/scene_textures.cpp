// scene_textures.cpp: loads, decodes, mip-maps and packs a scene's textures (scene_textures.h).
#include "texture/scene_textures.h"

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "image/exr_layers.h"
#include "texture/mip_chain.h"
#include "texture/texture_budget.h"
#include "util/errors.h"

namespace montecl {

bool sceneHasTextures(const Scene& scene) {
  for (const MaterialDesc& m : scene.materials)
    if (!m.albedoTexture.empty() || !m.alphaTexture.empty()) return true;
  return false;
}

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

std::vector<Triangle> alphaFlaggedTriangles(const std::vector<Triangle>& tris, const SceneTextures& textures) {
  if (!textures.anyAlpha()) return {};
  std::vector<Triangle> out = tris;
  for (Triangle& t : out) {
    const std::uint32_t m = glm::floatBitsToUint(t.v0.w);
    if (m < textures.materials.size() && textures.materials[m].alpha != MCL_NO_TEXTURE)
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
  }
}

void packTextures(SceneTextures& out, const std::vector<RgbaImage>& images, std::uint64_t budgetBytes,
                  std::vector<std::string>& warnings) {
  std::vector<std::vector<RgbaImage>> chains;
  std::vector<std::vector<std::uint64_t>> levelBytes;
  for (const RgbaImage& image : images) {
    chains.push_back(buildMipChain(image));
    levelBytes.emplace_back();
    for (const RgbaImage& level : chains.back()) levelBytes.back().push_back(level.texels.size() * 8u);
  }
  const std::vector<int> drop = finestLevelsToDrop(levelBytes, budgetBytes);
  std::ostringstream dropped;
  int droppedCount = 0;
  std::uint64_t texelCount = 0;
  for (std::size_t t = 0; t < chains.size(); ++t)
    for (std::size_t k = std::size_t(drop[t]); k < chains[t].size(); ++k) texelCount += chains[t][k].texels.size();
  if (texelCount > 0xffffffffull) throw RuntimeError("textures: more than 2^32 texels after the texture budget");
  out.texels.clear();
  out.texels.reserve(texelCount * 4);
  out.textures.clear();
  out.levels.clear();
  for (std::size_t t = 0; t < chains.size(); ++t) {
    const RgbaImage& base = chains[t][0];
    TextureDesc d{};
    d.firstLevel = std::uint32_t(out.levels.size());
    d.levelCount = std::uint32_t(chains[t].size() - std::size_t(drop[t]));
    d.dropped = std::uint32_t(drop[t]);
    d.lodBias = 0.5f * float(std::log2(double(base.width) * double(base.height)));
    out.textures.push_back(d);
    for (std::size_t k = std::size_t(drop[t]); k < chains[t].size(); ++k) {
      const RgbaImage& level = chains[t][k];
      out.levels.push_back(TextureLevel{std::uint32_t(out.texels.size() / 4), std::uint32_t(level.width),
                                        std::uint32_t(level.height), 0u});
      for (const glm::vec4& c : level.texels)
        for (int i = 0; i < 4; ++i) out.texels.push_back(floatToHalf(c[i]));
    }
    if (drop[t] > 0) {
      const RgbaImage& kept = chains[t][std::size_t(drop[t])];
      dropped << (droppedCount++ ? ", " : "") << (t < out.files.size() ? out.files[t] : "texture " + std::to_string(t))
              << " " << base.width << "x" << base.height << " -> " << kept.width << "x" << kept.height;
    }
  }
  if (droppedCount > 0) {
    std::uint64_t full = 0;
    for (const auto& levels : levelBytes)
      for (std::uint64_t b : levels) full += b;
    std::ostringstream w;
    w << "textures need " << ((full + (1u << 20) - 1) >> 20) << " MiB, over the texture budget of "
      << (budgetBytes >> 20) << " MiB (" << budgetBytes << " bytes): finest mip levels dropped from " << droppedCount
      << " texture" << (droppedCount > 1 ? "s" : "") << " (" << dropped.str() << "), now " << (out.bytes() >> 20)
      << " MiB; raise --texture-budget for full resolution";
    warnings.push_back(w.str());
  }
}

SceneTextures loadSceneTextures(const Scene& scene, std::uint64_t budgetBytes, std::vector<std::string>& warnings) {
  SceneTextures out;
  out.materials.resize(scene.materials.size());
  std::map<std::string, LayeredImage> files;  // each file read once
  std::map<std::pair<std::string, bool>, std::uint32_t> index;  // (file, sRGB-decoded) -> texture
  std::vector<RgbaImage> images;
  const auto read = [&](const MaterialDesc& m, const std::string& path, const char* key) -> const LayeredImage& {
    auto it = files.find(path);
    if (it != files.end()) return it->second;
    try {
      return files.emplace(path, readLayeredImage(path)).first->second;
    } catch (const InputError& e) {
      std::string why = e.what();
      const std::string prefix = path + ": ";
      if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
      throwInputError(path, "material '" + m.name + "' " + key, why);
    }
  };
  const auto texture = [&](const MaterialDesc& m, const std::string& path, const char* key, bool srgb) {
    const LayeredImage& image = read(m, path, key);
    const bool decode = srgb && isIntegerImage(image);
    auto [it, added] = index.emplace(std::make_pair(path, decode), std::uint32_t(images.size()));
    if (added) {
      images.push_back(rgbaFromImage(image, decode));
      out.files.push_back(path);
    }
    return it->second;
  };
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    if (!m.albedoTexture.empty()) out.materials[i].albedo = texture(m, m.albedoTexture, "map_Kd", true);
    if (!m.alphaTexture.empty()) {
      // Alpha is never sRGB-encoded: the file's alpha channel (shared with its colour texture),
      // else its first channel, read linear.
      const LayeredImage& image = read(m, m.alphaTexture, "map_d");
      const std::size_t nch = image.planes.size();
      const bool hasAlpha = nch == 2 || nch >= 4;
      out.materials[i].alpha = texture(m, m.alphaTexture, "map_d", hasAlpha);
      out.materials[i].alphaChannel = hasAlpha ? 3u : 0u;
    }
  }
  packTextures(out, images, budgetBytes, warnings);
  return out;
}

}  // namespace montecl
