// scene_textures.cpp: loads, decodes, mip-maps and packs a scene's textures (scene_textures.h).
#include "texture/scene_textures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

#include "image/exr_layers.h"
#include "image/image_read.h"
#include "scene/gltf_spec_gloss.h"
#include "texture/texel_codes.h"
#include "texture/bump_gradient.h"
#include "texture/mip_chain.h"
#include "texture/texture_budget.h"
#include "util/errors.h"
#include "util/parallel_for.h"

namespace montecl {

glm::vec4 specGlossTexel(glm::vec4 texel, glm::vec4 factors, glm::vec3 diffuse) {
  const MetalRoughFactors mr = metalRoughFromSpecGloss(diffuse, glm::vec3(texel) * glm::vec3(factors), texel.w * factors.w);
  return glm::vec4(0.0f, mr.roughness, mr.metallic, 1.0f);
}

namespace {

// A texture's mip pyramid (buildMipChain's levels) as RGBA half texels, level 0 first: what is kept
// of an image between reading it and packing (8 bytes a texel instead of a float image's 16).
struct HalfChain {
  int width = 0, height = 0;                    // of level 0
  std::vector<std::pair<int, int>> sizes;       // of each level
  std::vector<std::vector<std::uint16_t>> levels;
  std::vector<std::uint32_t> formats;           // of each level (MCL_TEXELS_*): 8-bit codes or half
  // A texture no image of this render reads (TextureUses), known by its size alone: it takes part
  // in the budget's choice of levels, as it would if it were loaded, so that the textures that are
  // loaded keep the same levels (the same image) whichever others are; it gets no TextureDesc.
  bool sizeOnly = false;
};

// The chain a w x h image would have, without texels.
HalfChain sizeOnlyChain(int w, int h) {
  HalfChain c;
  c.width = w;
  c.height = h;
  c.sizeOnly = true;
  for (int k = 0; k < mipLevelCount(w, h); ++k) c.sizes.push_back({std::max(1, w >> k), std::max(1, h >> k)});
  return c;
}

// The same levels as buildMipChain(image), each converted as soon as it exists (two float levels
// live at a time).
HalfChain halfChain(RgbaImage image) {
  HalfChain c;
  c.width = image.width;
  c.height = image.height;
  const int count = mipLevelCount(image.width, image.height);
  for (int k = 0; k < count; ++k) {
    if (k > 0) image = downsample(image);
    std::vector<std::uint16_t> half(image.texels.size() * 4);
    std::uint16_t* dst = half.data();
    for (const glm::vec4& t : image.texels)
      for (int i = 0; i < 4; ++i) *dst++ = floatToHalf(t[i]);
    c.sizes.push_back({image.width, image.height});
    // The finest level of an 8-bit image is its codes' decodes (texel_codes.h): 4 bytes a texel.
    std::vector<std::uint16_t> codes;
    const std::uint32_t format = k == 0 ? encodeTexelCodes(half, &codes) : MCL_TEXELS_HALF;
    c.formats.push_back(format);
    c.levels.push_back(format == MCL_TEXELS_HALF ? std::move(half) : std::move(codes));
  }
  return c;
}

// packTextures on converted chains: the texels grow level by level as each chain is freed, so the
// chains and the packed texels are not both held whole.
void packChains(SceneTextures& out, std::vector<HalfChain> chains, std::uint64_t budgetBytes,
                std::vector<std::string>& warnings) {
  const std::size_t count = chains.size();
  std::vector<std::vector<std::uint64_t>> levelBytes(count);
  std::uint64_t full = 0;
  for (std::size_t t = 0; t < count; ++t) {
    for (const auto& [w, h] : chains[t].sizes) levelBytes[t].push_back(std::uint64_t(w) * std::uint64_t(h) * 8u);
    for (std::uint64_t b : levelBytes[t]) full += b;
  }
  const std::vector<int> drop = finestLevelsToDrop(levelBytes, budgetBytes);
  out.textures.clear();
  out.levels.clear();
  std::uint64_t texelCount = 0;
  // Where each level starts in the texel buffer, in ushorts: after the code tables, a half level
  // at a multiple of 4 (its offset counts 8-byte texels), an 8-bit one at a multiple of 2 (4-byte).
  std::uint64_t at = MCL_TEXEL_TABLES;
  std::vector<std::vector<std::uint64_t>> starts(count);
  std::ostringstream dropped;
  int droppedCount = 0;
  for (std::size_t t = 0; t < count; ++t) {
    const HalfChain& c = chains[t];
    if (c.sizeOnly) continue;
    const std::size_t index = out.textures.size();  // files[] names the loaded textures only
    TextureDesc d{};
    d.firstLevel = std::uint32_t(out.levels.size());
    d.levelCount = std::uint32_t(c.sizes.size() - std::size_t(drop[t]));
    d.dropped = std::uint32_t(drop[t]);
    d.lodBias = 0.5f * float(std::log2(double(c.width) * double(c.height)));
    d.uvRow0 = float4(1.0f, 0.0f, 0.0f, glm::uintBitsToFloat(MCL_WRAP_REPEAT));  // read as it is
    d.uvRow1 = float4(0.0f, 1.0f, 0.0f, glm::uintBitsToFloat(MCL_WRAP_REPEAT));
    out.textures.push_back(d);
    for (std::size_t k = std::size_t(drop[t]); k < c.sizes.size(); ++k) {
      if (texelCount + std::uint64_t(c.sizes[k].first) * c.sizes[k].second > 0xffffffffull)
        throw RuntimeError("textures: more than 2^32 texels after the texture budget; lower --texture-budget");
      const std::uint64_t n = std::uint64_t(c.sizes[k].first) * c.sizes[k].second;
      const std::uint64_t unit = c.formats[k] == MCL_TEXELS_HALF ? 4u : 2u;  // ushorts a texel
      at = (at + unit - 1) / unit * unit;
      out.levels.push_back(TextureLevel{std::uint32_t(at / unit), std::uint32_t(c.sizes[k].first),
                                        std::uint32_t(c.sizes[k].second), c.formats[k]});
      starts[t].push_back(at);
      at += unit * n;
      texelCount += n;
    }
    if (drop[t] > 0)
      dropped << (droppedCount++ ? ", " : "") << (index < out.files.size() ? out.files[index] : "texture " + std::to_string(index))
              << " " << c.width << "x" << c.height << " -> " << c.sizes[drop[t]].first << "x"
              << c.sizes[drop[t]].second;
  }
  // The code tables, then the levels in table order (offsets ascending, zeros where a level's
  // start is rounded up): appended, each chain freed once copied.
  out.texels.clear();
  out.texels.reserve(at);
  out.texels.assign(texelCodeTables().begin(), texelCodeTables().end());
  for (std::size_t t = 0; t < count; ++t) {
    for (std::size_t k = std::size_t(drop[t]), j = 0; k < chains[t].levels.size() && !chains[t].sizeOnly; ++k, ++j) {
      out.texels.resize(starts[t][j], 0);
      out.texels.insert(out.texels.end(), chains[t].levels[k].begin(), chains[t].levels[k].end());
    }
    chains[t] = HalfChain{};
  }
  if (droppedCount > 0) {
    std::ostringstream w;
    w << "textures need " << ((full + (1u << 20) - 1) >> 20) << " MiB, over the texture budget of "
      << (budgetBytes >> 20) << " MiB (" << budgetBytes << " bytes): finest mip levels dropped from " << droppedCount
      << " texture" << (droppedCount > 1 ? "s" : "") << " (" << dropped.str() << "), now " << (out.bytes() >> 20)
      << " MiB; raise --texture-budget for full resolution";
    warnings.push_back(w.str());
  }
}

static_assert(MCL_WRAP_REPEAT == 0u && MCL_WRAP_CLAMP == 1u && MCL_WRAP_MIRROR == 2u, "TextureSampling wrap values");

// Every texture use with its own transform or wrap modes gets a TextureDesc of its own over the
// same levels (one per distinct image and sampling); uses without one keep the image's.
void applySampling(SceneTextures& out, const Scene& scene, const TextureUses& uses) {
  std::map<std::pair<std::uint32_t, std::string>, std::uint32_t> views;
  const auto view = [&](std::uint32_t& index, const TextureSampling& s) {
    if (index == MCL_NO_TEXTURE || s.identity()) return;
    std::string key(sizeof s, '\0');
    std::memcpy(key.data(), &s, sizeof s);
    auto [it, added] = views.emplace(std::make_pair(index, key), std::uint32_t(out.textures.size()));
    if (added) {
      TextureDesc d = out.textures[index];
      d.uvRow0 = float4(s.row0, glm::uintBitsToFloat(s.wrapS));
      d.uvRow1 = float4(s.row1, glm::uintBitsToFloat(s.wrapT));
      out.textures.push_back(d);
      out.files.push_back(index < out.files.size() ? out.files[index] : "");
    }
    index = it->second;
  };
  for (std::size_t i = 0; i < scene.materials.size() && i < out.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    MaterialTextures& t = out.materials[i];
    if (uses.reflectance) view(t.albedo, m.albedoSampling);
    if (uses.emission) view(t.emission, m.emissionSampling);
    if (uses.reflectance) view(t.metallicRoughness, m.metallicRoughnessSampling);
    if (uses.reflectance) view(t.transmission, m.transmissionSampling);
    if (uses.normal) view(t.normal, m.normalSampling);
    if (uses.normal) view(t.bump, m.bumpSampling);
    view(t.alpha, m.alphaSampling);
  }
}

}  // namespace

void packTextures(SceneTextures& out, std::vector<RgbaImage> images, std::uint64_t budgetBytes,
                  std::vector<std::string>& warnings) {
  std::vector<HalfChain> chains(images.size());
  parallelFor(images.size(), 0, 1, [&](std::size_t t) { chains[t] = halfChain(std::move(images[t])); });
  packChains(out, std::move(chains), budgetBytes, warnings);
}

SceneTextures loadSceneTextures(const Scene& scene, std::uint64_t budgetBytes, std::vector<std::string>& warnings,
                                TextureUses uses) {
  SceneTextures out;
  out.materials.resize(scene.materials.size());
  // Every file once, in first-use order, with the first material and key naming it in errors.
  struct File {
    std::string path, material;
    const char* key = "";
    bool asColour = false, asAlpha = false;
    bool asLinear = false;  // a data texture read linear: a File of its own (fileIndex key: linearKey)
    // A specular-glossiness map read as a metallic-roughness one (MaterialDesc::specGlossMap): a
    // File of its own per (path, factors), each texel converted (specGlossTexel).
    bool specGloss = false;
    glm::vec4 sg{1.0f};
    glm::vec3 sgDiffuse{1.0f};
    // A normal map: a File of its own per (path, scale), texels the decoded tangent-space vectors
    // with the scale baked in (normal_map.h).
    bool asNormal = false;
    float normalScale = 1.0f;
    // A bump map: a File of its own per (path, scale, wrap modes), texels the scaled height
    // gradient (bump_gradient.h), whose differences follow the wrap modes.
    bool asBump = false;
    float bumpScale = 1.0f;
    std::uint32_t wrapS = 0, wrapT = 0;
    // After reading: the file's textures (sRGB-decoded colour and/or linear alpha; one when they
    // coincide), mip-mapped, and whether it has an alpha channel.
    std::vector<HalfChain> images;
    bool integer = false, hasAlpha = false;
    bool alphaBelowOne = false;  // some texel's alpha is below 1 (read for colour textures)
    // Whether an image of this render reads the file's colour (albedo, emission) or its data
    // (metallic-roughness, normal map) texture: otherwise that texture is a size-only chain.
    bool colourRead = false, dataRead = false;
    std::string error;
  };
  std::vector<File> files;
  std::map<std::string, std::size_t> fileIndex;
  const auto plainLinearKey = [](const std::string& path) { return path + std::string(1, '\0') + "linear"; };
  const auto linearKey = [&](const MaterialDesc& m) {
    if (!m.specGlossMap) return plainLinearKey(m.metallicRoughnessTexture);
    char key[160];
    std::snprintf(key, sizeof key, "spec-gloss %a %a %a %a %a %a %a", double(m.specGloss.x), double(m.specGloss.y),
                  double(m.specGloss.z), double(m.specGloss.w), double(m.specGlossDiffuse.x), double(m.specGlossDiffuse.y),
                  double(m.specGlossDiffuse.z));
    return m.metallicRoughnessTexture + std::string(1, '\0') + key;
  };
  // A data texture (path, under fkey): the metallic-roughness one (specGloss: converted) or the
  // transmission one (never: a texture of both shares the File).
  const auto useLinear = [&](const MaterialDesc& m, const std::string& path, const std::string& fkey, bool specGloss,
                             const char* key, bool read) {
    auto [it, added] = fileIndex.emplace(fkey, files.size());
    if (added) {
      files.emplace_back();
      files.back().path = path;
      files.back().material = m.name;
      files.back().key = key;
      files.back().asLinear = true;
      files.back().specGloss = specGloss;
      files.back().sg = m.specGloss;
      files.back().sgDiffuse = m.specGlossDiffuse;
    }
    files[it->second].dataRead |= read;
  };
  const auto use = [&](const MaterialDesc& m, const std::string& path, const char* key, bool colour, bool read) {
    auto [it, added] = fileIndex.emplace(path, files.size());
    if (added) {
      files.emplace_back();
      files.back().path = path;
      files.back().material = m.name;
      files.back().key = key;
    }
    (colour ? files[it->second].asColour : files[it->second].asAlpha) = true;
    if (colour) files[it->second].colourRead |= read;
  };
  const auto normalKey = [](const MaterialDesc& m) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%a", double(m.normalScale));
    return m.normalTexture + std::string(1, '\0') + "normal " + scale;
  };
  const auto useNormal = [&](const MaterialDesc& m, bool read) {
    auto [it, added] = fileIndex.emplace(normalKey(m), files.size());
    if (added) {
      files.emplace_back();
      files.back().path = m.normalTexture;
      files.back().material = m.name;
      files.back().key = "normal texture";
      files.back().asNormal = true;
      files.back().normalScale = m.normalScale;
    }
    files[it->second].dataRead |= read;
  };
  const auto bumpKey = [](const MaterialDesc& m) {
    char key[64];
    std::snprintf(key, sizeof key, "bump %a %u %u", double(m.bumpScale), unsigned(m.bumpSampling.wrapS),
                  unsigned(m.bumpSampling.wrapT));
    return m.bumpTexture + std::string(1, '\0') + key;
  };
  const auto useBump = [&](const MaterialDesc& m, bool read) {
    auto [it, added] = fileIndex.emplace(bumpKey(m), files.size());
    if (added) {
      files.emplace_back();
      files.back().path = m.bumpTexture;
      files.back().material = m.name;
      files.back().key = "bump";
      files.back().asBump = true;
      files.back().bumpScale = m.bumpScale;
      files.back().wrapS = m.bumpSampling.wrapS;
      files.back().wrapT = m.bumpSampling.wrapT;
    }
    files[it->second].dataRead |= read;
  };
  // Every file in the order a render that reads every texture lists them, marked with what this
  // render reads of it (the budget's choice of levels depends on that order).
  for (const MaterialDesc& m : scene.materials) {
    if (!m.albedoTexture.empty()) use(m, m.albedoTexture, "map_Kd", true, uses.reflectance);
    if (!m.alphaTexture.empty()) use(m, m.alphaTexture, "map_d", false, true);
    if (!m.emissionTexture.empty()) use(m, m.emissionTexture, "map_Ke", true, uses.emission);
    if (!m.metallicRoughnessTexture.empty())
      useLinear(m, m.metallicRoughnessTexture, linearKey(m), m.specGlossMap,
                m.specGlossMap ? "specularGlossinessTexture" : "metallicRoughnessTexture", uses.reflectance);
    if (!m.transmissionTexture.empty())
      useLinear(m, m.transmissionTexture, plainLinearKey(m.transmissionTexture), false, "transmissionTexture",
                uses.reflectance);
    if (!m.normalTexture.empty()) useNormal(m, uses.normal);
    if (usesBumpMap(m)) useBump(m, uses.normal);
  }
  const auto decoded = [](const File& f) { return f.asAlpha || f.colourRead || f.dataRead; };
  // Nothing to decode: no texture at all (the others' sizes would choose nothing).
  if (std::none_of(files.begin(), files.end(), decoded)) files.clear();
  // A file whose finest level alone is over the budget is refused from its header, before it is
  // decoded: the budget would drop that level anyway, and a 69-byte PNG can declare 16384 x 16384.
  const ImageSizeCheck fitsBudget = [budgetBytes](int w, int h, int) -> std::string {
    const std::uint64_t bytes = std::uint64_t(w) * std::uint64_t(h) * 8u;  // half-float RGBA texels
    if (bytes <= budgetBytes) return "";
    return "declares " + std::to_string(w) + "x" + std::to_string(h) + " texels, " + std::to_string((bytes + (1u << 20) - 1) >> 20) +
           " MiB at full resolution, over the texture budget of " + std::to_string(budgetBytes >> 20) + " MiB (" +
           std::to_string(budgetBytes) + " bytes); raise --texture-budget or use a smaller image";
  };
  // Read, convert and mip-map in parallel (one file per task); the pixels as read and the float
  // levels are dropped at once (only the half-float pyramids are kept until packing).
  if (!files.empty()) parallelChunks(files.size(), 0, 1, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      File& f = files[i];
      const auto embedded = scene.embeddedImages.find(f.path);
      if (!decoded(f)) {  // only its size, from the header (no pixel is decoded)
        // A file that cannot be read would fail a render that reads it; here it only counts as
        // its size, when the header gives one.
        const ImageSize size = readImageSize(f.path, embedded != scene.embeddedImages.end() ? &embedded->second : nullptr);
        if (size.width > 0 && size.height > 0) f.images.push_back(sizeOnlyChain(size.width, size.height));
        continue;
      }
      try {
        const LayeredImage image = embedded != scene.embeddedImages.end()
                                       ? readImageMemory(f.path, embedded->second, fitsBudget)
                                       : readLayeredImage(f.path, fitsBudget);
        // The environment map's rule, and texels are half floats: over 65504 would be infinite.
        std::vector<const std::vector<float>*> used;
        for (std::size_t c = 0; c < std::min<std::size_t>(image.planes.size(), 4); ++c) used.push_back(&image.planes[c]);
        const std::string bad = badPixelValue(used, image.width, 65504.0f);
        if (!bad.empty()) throwInputError(f.path, "", bad);
        f.integer = isIntegerImage(image);
        f.hasAlpha = image.planes.size() == 2 || image.planes.size() >= 4;
        if (f.hasAlpha && f.asColour) {
          const std::vector<float>& a = image.planes[image.planes.size() == 2 ? 1 : 3];
          f.alphaBelowOne = std::any_of(a.begin(), a.end(), [](float v) { return v < 1.0f; });
        }
        // Colour: sRGB-decoded when integer. Alpha: the alpha channel (shared with the colour
        // texture), else the first channel, never decoded.
        const bool colourDecode = f.integer;
        const bool alphaDecode = f.hasAlpha && f.integer;
        if (f.asColour && !f.colourRead && !(f.asAlpha && alphaDecode == colourDecode))
          f.images.push_back(sizeOnlyChain(image.width, image.height));  // the colour texture, not read
        else if (f.asColour || (f.asAlpha && alphaDecode == colourDecode))
          f.images.push_back(halfChain(rgbaFromImage(image, colourDecode)));
        if (f.asAlpha && alphaDecode != colourDecode) f.images.push_back(halfChain(rgbaFromImage(image, alphaDecode)));
        if (f.asLinear && !f.specGloss) f.images.push_back(halfChain(rgbaFromImage(image, false)));
        if (f.asLinear && f.specGloss) {  // the specular colour sRGB-decoded (when integer), glossiness linear
          RgbaImage t = rgbaFromImage(image, f.integer);
          for (glm::vec4& x : t.texels) x = specGlossTexel(x, f.sg, f.sgDiffuse);
          f.images.push_back(halfChain(std::move(t)));
        }
        if (f.asNormal) {  // linear texels (never sRGB), decoded: n = ((2r - 1) s, (2g - 1) s, 2b - 1)
          RgbaImage n = rgbaFromImage(image, false);
          const float sc = f.normalScale;
          for (glm::vec4& t : n.texels) t = glm::vec4((2.0f * t.x - 1.0f) * sc, (2.0f * t.y - 1.0f) * sc, 2.0f * t.z - 1.0f, 1.0f);
          f.images.push_back(halfChain(std::move(n)));
        }
        if (f.asBump)  // heights are data: linear, never sRGB-decoded
          f.images.push_back(halfChain(bumpGradient(rgbaFromImage(image, false), f.bumpScale, f.wrapS, f.wrapT)));
      } catch (const InputError& e) {
        std::string why = e.what();
        const std::string prefix = f.path + ": ";
        f.error = why.rfind(prefix, 0) == 0 ? why.substr(prefix.size()) : why;
      }
    }
  }, 1);
  for (const File& f : files)
    if (!f.error.empty()) throwInputError(f.path, "material '" + f.material + "' " + f.key, f.error);
  // Texture indices in file order, counting the loaded textures only; sizeBefore[i][j]: how many
  // of file i's textures before its j-th are size-only.
  std::vector<HalfChain> images;
  std::vector<std::uint32_t> first(files.size());
  std::vector<std::vector<std::uint32_t>> sizeOnlyBefore(files.size());
  std::uint32_t loaded = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    first[i] = loaded;
    std::uint32_t skipped = 0;
    for (HalfChain& im : files[i].images) {
      sizeOnlyBefore[i].push_back(skipped);
      if (im.sizeOnly) {
        ++skipped;
      } else {
        ++loaded;
        out.files.push_back(files[i].path);
      }
      images.push_back(std::move(im));
    }
    files[i].images.clear();
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    if (uses.reflectance && !m.albedoTexture.empty()) out.materials[i].albedo = first[fileIndex.at(m.albedoTexture)];
    if (uses.emission && !m.emissionTexture.empty()) out.materials[i].emission = first[fileIndex.at(m.emissionTexture)];
    if (uses.reflectance && !m.metallicRoughnessTexture.empty())
      out.materials[i].metallicRoughness = first[fileIndex.at(linearKey(m))];
    if (uses.reflectance && !m.transmissionTexture.empty())
      out.materials[i].transmission = first[fileIndex.at(plainLinearKey(m.transmissionTexture))];
    if (uses.normal && !m.normalTexture.empty()) out.materials[i].normal = first[fileIndex.at(normalKey(m))];
    if (uses.normal && usesBumpMap(m)) out.materials[i].bump = first[fileIndex.at(bumpKey(m))];
    if (!m.alphaTexture.empty()) {
      const std::size_t k = fileIndex.at(m.alphaTexture);
      const File& f = files[k];
      // The second texture of a file is its linear alpha variant (see above); a colour texture
      // before it that is not read is size-only.
      const std::size_t j = f.asColour && (f.hasAlpha && f.integer) != f.integer ? 1u : 0u;
      out.materials[i].alpha = first[k] + std::uint32_t(j) - (j < sizeOnlyBefore[k].size() ? sizeOnlyBefore[k][j] : 0u);
      out.materials[i].alphaChannel = f.hasAlpha ? 3u : 0u;
    }
  }
  // An MTL map_Kd with alpha below 1 and no map_d renders opaque (MTL cuts out only with map_d):
  // one warning, at the first such material, saying how to cut it out.
  std::size_t uncut = 0;
  std::string firstUncut;
  for (const MaterialDesc& m : scene.materials)
    if (uses.reflectance && !m.cutoutHint.empty() && m.alphaTexture.empty() && !m.albedoTexture.empty() &&
        files[fileIndex.at(m.albedoTexture)].alphaBelowOne && uncut++ == 0)
      firstUncut = m.cutoutHint;
  if (uncut > 0)
    warnings.push_back(firstUncut + ": the texture's alpha is below 1 in places, but without map_d the material renders "
                       "opaque; to cut it out, add 'map_d' naming the same file to the material (or give the mesh entry's "
                       "\"material\": {\"alpha_texture\": ...})" +
                       (uncut > 1 ? " (" + std::to_string(uncut - 1) + " more materials like it)" : std::string()));
  packChains(out, std::move(images), budgetBytes, warnings);
  applySampling(out, scene, uses);
  return out;
}

}  // namespace montecl
