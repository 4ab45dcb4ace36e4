// scene_textures.cpp: loads, decodes, mip-maps and packs a scene's textures (scene_textures.h).
#include "texture/scene_textures.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "image/exr_layers.h"
#include "texture/mip_chain.h"
#include "texture/texture_budget.h"
#include "util/errors.h"
#include "util/parallel_for.h"

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

namespace {

// Width and height of each mip level of a w x h image (level 0 first), as buildMipChain makes them.
std::vector<std::pair<int, int>> levelSizes(int w, int h) {
  std::vector<std::pair<int, int>> sizes{{w, h}};
  const int count = mipLevelCount(w, h);
  while (int(sizes.size()) < count) {
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    sizes.push_back({w, h});
  }
  return sizes;
}

}  // namespace

void packTextures(SceneTextures& out, std::vector<RgbaImage> images, std::uint64_t budgetBytes,
                  std::vector<std::string>& warnings) {
  const std::size_t count = images.size();
  std::vector<std::vector<std::pair<int, int>>> sizes(count);
  std::vector<std::vector<std::uint64_t>> levelBytes(count);
  std::uint64_t full = 0;
  for (std::size_t t = 0; t < count; ++t) {
    sizes[t] = levelSizes(images[t].width, images[t].height);
    for (const auto& [w, h] : sizes[t]) levelBytes[t].push_back(std::uint64_t(w) * std::uint64_t(h) * 8u);
    for (std::uint64_t b : levelBytes[t]) full += b;
  }
  const std::vector<int> drop = finestLevelsToDrop(levelBytes, budgetBytes);
  // The tables first (offsets known from the sizes), then every texture's kept levels in parallel.
  out.textures.clear();
  out.levels.clear();
  std::uint64_t texelCount = 0;
  std::ostringstream dropped;
  int droppedCount = 0;
  for (std::size_t t = 0; t < count; ++t) {
    TextureDesc d{};
    d.firstLevel = std::uint32_t(out.levels.size());
    d.levelCount = std::uint32_t(sizes[t].size() - std::size_t(drop[t]));
    d.dropped = std::uint32_t(drop[t]);
    d.lodBias = 0.5f * float(std::log2(double(images[t].width) * double(images[t].height)));
    out.textures.push_back(d);
    for (std::size_t k = std::size_t(drop[t]); k < sizes[t].size(); ++k) {
      if (texelCount + std::uint64_t(sizes[t][k].first) * sizes[t][k].second > 0xffffffffull)
        throw RuntimeError("textures: more than 2^32 texels after the texture budget; lower --texture-budget");
      out.levels.push_back(TextureLevel{std::uint32_t(texelCount), std::uint32_t(sizes[t][k].first),
                                        std::uint32_t(sizes[t][k].second), 0u});
      texelCount += std::uint64_t(sizes[t][k].first) * sizes[t][k].second;
    }
    if (drop[t] > 0)
      dropped << (droppedCount++ ? ", " : "") << (t < out.files.size() ? out.files[t] : "texture " + std::to_string(t))
              << " " << images[t].width << "x" << images[t].height << " -> " << sizes[t][drop[t]].first << "x"
              << sizes[t][drop[t]].second;
  }
  out.texels.assign(texelCount * 4, 0);
  if (count > 0) parallelFor(count, 0, 1, [&](std::size_t t) {
    std::vector<RgbaImage> chain = buildMipChain(std::move(images[t]));
    const TextureDesc& d = out.textures[t];
    for (std::uint32_t k = 0; k < d.levelCount; ++k) {
      const RgbaImage& level = chain[d.dropped + k];
      std::uint16_t* dst = &out.texels[std::size_t(out.levels[d.firstLevel + k].offset) * 4];
      for (const glm::vec4& c : level.texels)
        for (int i = 0; i < 4; ++i) *dst++ = floatToHalf(c[i]);
    }
  });
  if (droppedCount > 0) {
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
  // Every file once, in first-use order, with the first material and key naming it in errors.
  struct File {
    std::string path, material;
    const char* key = "";
    bool asColour = false, asAlpha = false;
    // After reading: the file's textures (sRGB-decoded colour and/or linear alpha; one when they
    // coincide) and whether it has an alpha channel.
    std::vector<RgbaImage> images;
    bool integer = false, hasAlpha = false;
    std::string error;
  };
  std::vector<File> files;
  std::map<std::string, std::size_t> fileIndex;
  const auto use = [&](const MaterialDesc& m, const std::string& path, const char* key, bool colour) {
    auto [it, added] = fileIndex.emplace(path, files.size());
    if (added) {
      files.emplace_back();
      files.back().path = path;
      files.back().material = m.name;
      files.back().key = key;
    }
    (colour ? files[it->second].asColour : files[it->second].asAlpha) = true;
  };
  for (const MaterialDesc& m : scene.materials) {
    if (!m.albedoTexture.empty()) use(m, m.albedoTexture, "map_Kd", true);
    if (!m.alphaTexture.empty()) use(m, m.alphaTexture, "map_d", false);
  }
  // Read and convert in parallel (one file per task); the pixels as read are dropped at once.
  if (!files.empty()) parallelChunks(files.size(), 0, 1, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      File& f = files[i];
      try {
        const LayeredImage image = readLayeredImage(f.path);
        f.integer = isIntegerImage(image);
        f.hasAlpha = image.planes.size() == 2 || image.planes.size() >= 4;
        // Colour: sRGB-decoded when integer. Alpha: the alpha channel (shared with the colour
        // texture), else the first channel, never decoded.
        const bool colourDecode = f.integer;
        const bool alphaDecode = f.hasAlpha && f.integer;
        if (f.asColour || (f.asAlpha && alphaDecode == colourDecode)) f.images.push_back(rgbaFromImage(image, colourDecode));
        if (f.asAlpha && alphaDecode != colourDecode) f.images.push_back(rgbaFromImage(image, alphaDecode));
      } catch (const InputError& e) {
        std::string why = e.what();
        const std::string prefix = f.path + ": ";
        f.error = why.rfind(prefix, 0) == 0 ? why.substr(prefix.size()) : why;
      }
    }
  }, 1);
  for (const File& f : files)
    if (!f.error.empty()) throwInputError(f.path, "material '" + f.material + "' " + f.key, f.error);
  // Texture indices in file order.
  std::vector<RgbaImage> images;
  std::vector<std::uint32_t> first(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    first[i] = std::uint32_t(images.size());
    for (RgbaImage& im : files[i].images) {
      images.push_back(std::move(im));
      out.files.push_back(files[i].path);
    }
    files[i].images.clear();
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    if (!m.albedoTexture.empty()) out.materials[i].albedo = first[fileIndex.at(m.albedoTexture)];
    if (!m.alphaTexture.empty()) {
      const std::size_t k = fileIndex.at(m.alphaTexture);
      const File& f = files[k];
      // The second texture of a file is its linear alpha variant (see above).
      const bool second = f.asColour && (f.hasAlpha && f.integer) != f.integer;
      out.materials[i].alpha = first[k] + (second ? 1u : 0u);
      out.materials[i].alphaChannel = f.hasAlpha ? 3u : 0u;
    }
  }
  packTextures(out, std::move(images), budgetBytes, warnings);
  return out;
}

}  // namespace montecl
