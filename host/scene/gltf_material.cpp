// gltf_material.cpp: GltfMaterials (gltf_material.h): a glTF model's materials into MaterialDesc.
#include "scene/gltf_material.h"

#include <cmath>

#include "scene/gltf_clearcoat.h"
#include "scene/gltf_model.h"
#include "scene/gltf_sheen.h"
#include "scene/gltf_spec_gloss.h"
#include "scene/gltf_texture_info.h"
#include "scene/gltf_transmission.h"

namespace montecl {
namespace {

const char* const kSpecGloss = "KHR_materials_pbrSpecularGlossiness";
const char* const kSpecular = "KHR_materials_specular";

std::string materialWhere(std::size_t i) { return "materials[" + std::to_string(i) + "]"; }

glm::vec3 factor3(const std::vector<double>& f, double scale) {
  return f.size() >= 3 ? glm::vec3(float(f[0] * scale), float(f[1] * scale), float(f[2] * scale)) : glm::vec3(0.0f);
}

// ext[key]: a number, or fallback when absent; at names the key in messages.
double extNumber(const std::string& file, const std::string& at, const tinygltf::Value& ext, const char* key, double fallback) {
  if (!ext.IsObject() || !ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  const double x = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
  if (!std::isfinite(x)) loadFail(file, at + "." + key, "must be a finite number");
  return x;
}

// ext[key]: an array of n finite numbers in [0, 1] (a colour factor), or fallback when absent.
glm::vec4 extColour(const std::string& file, const std::string& at, const tinygltf::Value& ext, const char* key, int n,
                    glm::vec4 fallback) {
  if (!ext.IsObject() || !ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsArray() || v.ArrayLen() != std::size_t(n))
    loadFail(file, at + "." + key, "must be an array of " + std::to_string(n) + " numbers");
  glm::vec4 out = fallback;
  for (int c = 0; c < n; ++c) {
    const tinygltf::Value& x = v.Get(c);
    const double d = x.IsNumber() ? x.GetNumberAsDouble() : std::nan("");
    if (!(d >= 0.0 && d <= 1.0)) loadFail(file, at + "." + key, "must hold numbers in [0, 1]");
    out[c] = float(d);
  }
  return out;
}

// A textureInfo inside an extension object: its index, texCoord and extensions (-1: none given).
struct ExtTexture {
  int index = -1, texCoord = 0;
  tinygltf::ExtensionMap extensions;
};
ExtTexture extTexture(const std::string& file, const std::string& at, const tinygltf::Value& ext, const char* key) {
  ExtTexture t;
  if (!ext.IsObject() || !ext.Has(key)) return t;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsObject() || !v.Has("index") || !v.Get("index").IsInt() || v.Get("index").GetNumberAsInt() < 0)
    loadFail(file, at + "." + key, "must be a textureInfo with an index >= 0");
  t.index = v.Get("index").GetNumberAsInt();
  if (v.Has("texCoord")) {
    if (!v.Get("texCoord").IsInt() || v.Get("texCoord").GetNumberAsInt() < 0)
      loadFail(file, at + "." + key + ".texCoord", "must be a whole number >= 0");
    t.texCoord = v.Get("texCoord").GetNumberAsInt();
  }
  if (v.Has("extensions") && v.Get("extensions").IsObject())
    for (const std::string& k : v.Get("extensions").Keys()) t.extensions[k] = v.Get("extensions").Get(k);
  return t;
}

// KHR_materials_specular (ext; null: absent) where it maps onto a kind exactly: specularFactor 0 on
// a dielectric (metallic 0, no metallic-roughness texture, no transmission) leaves glTF's BSDF the
// Lambertian base colour alone: the diffuse kind. The defaults (factor 1, colour white) change
// nothing. Anything else would change metal_rough's dielectric F0 (0.04, fixed in the kind): warned.
void applyGltfSpecular(const std::string& file, const std::string& where, const tinygltf::Value* ext,
                       const tinygltf::Material& g, MaterialDesc& d, KindWarnings& unused) {
  if (!ext) return;
  const std::string at = where + ".extensions." + kSpecular;
  const double factor = extNumber(file, at, *ext, "specularFactor", 1.0);
  if (!(factor >= 0.0 && factor <= 1.0)) loadFail(file, at + ".specularFactor", "must be in [0, 1]");
  const glm::vec3 colour = glm::vec3(extColour(file, at, *ext, "specularColorFactor", 3, glm::vec4(1.0f)));
  const bool textured = ext->IsObject() && (ext->Has("specularTexture") || ext->Has("specularColorTexture"));
  const bool transmits = g.extensions.count("KHR_materials_transmission") > 0;
  if (factor == 0.0 && !ext->Has("specularTexture") && d.metallic == 0.0f && d.metallicRoughnessTexture.empty() &&
      !transmits && (d.kind == MCL_MATERIAL_diffuse || d.kind == MCL_MATERIAL_metal_rough)) {
    d.kind = MCL_MATERIAL_diffuse;  // no specular lobe: Lambert of the base colour, exactly
    d.roughness = 1.0f;
    return;
  }
  if (factor == 1.0 && colour == glm::vec3(1.0f) && !textured) return;
  unused.add("specular", where, std::string(kSpecular) +
                                    " not used here (metal_rough's dielectric F0 stays 0.04; only specularFactor 0 on a "
                                    "non-metal without transmission maps onto a kind: Lambert)");
}

}  // namespace

bool gltfMaterialExtensionRead(const std::string& name) {
  return name == kSpecGloss || name == kSpecular || name == "KHR_materials_emissive_strength" ||
         name == "KHR_materials_unlit" || gltfTransmissionExtension(name) || gltfClearcoatExtension(name) ||
         gltfSheenExtension(name);
}

GltfMaterials::GltfMaterials(const std::string& file, const tinygltf::Model& m, Scene& scene, KindWarnings& unused)
    : file_(file), m_(m), scene_(scene), unused_(unused), made_(m.materials.size(), -1), uvSet_(m.materials.size(), 0),
      uvSetKey_(m.materials.size()) {}

int GltfMaterials::uvSet(int material) const {
  return material >= 0 && std::size_t(material) < uvSet_.size() ? uvSet_[std::size_t(material)] : 0;
}

const std::string& GltfMaterials::uvSetKey(int material) const { return uvSetKey_.at(std::size_t(material)); }

std::uint32_t GltfMaterials::index(int material) {
  if (material < 0 || std::size_t(material) >= m_.materials.size()) {
    // glTF's default material: every factor at its default (white, metallic 1, roughness 1).
    if (default_ < 0) {
      MaterialDesc d("glTF default material", glm::vec3(1.0f));
      d.kind = MCL_MATERIAL_metal_rough;
      d.metallic = 1.0f;
      d.roughness = 1.0f;
      default_ = std::int64_t(scene_.materials.size());
      scene_.materials.push_back(d);
    }
    return std::uint32_t(default_);
  }
  const std::size_t i = std::size_t(material);
  if (made_[i] < 0) {
    MaterialDesc d = read(i);
    made_[i] = std::int64_t(scene_.materials.size());
    scene_.materials.push_back(std::move(d));
  }
  return std::uint32_t(made_[i]);
}

std::string GltfMaterials::texturePath(std::size_t i, int tex, int texCoord, const tinygltf::ExtensionMap& extensions,
                                       const std::string& key, TextureSampling& sampling) {
  const std::string where = materialWhere(i);
  if (tex < 0 || static_cast<std::size_t>(tex) >= m_.textures.size())
    loadFail(file_, where, key.substr(key.rfind('.') + 1) + " index out of range");
  const std::string infoKey = where + "." + key;
  const GltfTextureRead read = readGltfTextureInfo(file_, m_, tex, texCoord, extensions, infoKey);
  sampling = read.sampling;
  // Every texture of a material reads one TEXCOORD set.
  if (read.texCoord != uvSet_[i] && !uvSetKey_[i].empty())
    unused_.add("uv sets", where, "textures read TEXCOORD_" + std::to_string(uvSet_[i]) + " and TEXCOORD_" +
                                      std::to_string(read.texCoord) + ": montecl reads one set per material (TEXCOORD_" +
                                      std::to_string(uvSet_[i]) + " used for all)");
  else if (uvSetKey_[i].empty()) uvSet_[i] = read.texCoord, uvSetKey_[i] = infoKey + ".texCoord";
  const tinygltf::Texture& t = m_.textures[static_cast<std::size_t>(tex)];
  const std::string image = "images[" + std::to_string(t.source) + "]";
  if (t.source < 0 || static_cast<std::size_t>(t.source) >= m_.images.size())
    loadFail(file_, "textures[" + std::to_string(tex) + "]", "source image missing or out of range");
  std::string path = gltfImagePath(file_, m_, t.source, scene_);
  if (scene_.embeddedImages.count(path) == 0) {  // a file of its own: an input, checked now
    const std::string problem = fileProblem(path), found = problem.empty() ? "" : findIgnoringCase(path);
    if (!found.empty()) {
      unused_.add("case", image, "'" + path + "' not found as written; using '" + found + "' (the names differ in case)");
      path = found;
    } else if (!problem.empty()) {  // recorded once per image; the material goes without it
      if (missingImages_.insert(t.source).second)
        noteMissingTexture(scene_.missingTextures, {file_, image, "cannot open '" + path + "': " + problem, image + " '" + path + "'"});
      return std::string();
    }
    scene_.inputFiles.push_back(path);
  }
  return path;
}

MaterialDesc GltfMaterials::read(std::size_t i) {
  const tinygltf::Material& g = m_.materials[i];
  const std::string where = materialWhere(i);
  const auto& pbr = g.pbrMetallicRoughness;
  const auto extension = [&](const char* name) -> const tinygltf::Value* {
    const auto it = g.extensions.find(name);
    return it == g.extensions.end() ? nullptr : &it->second;
  };
  const tinygltf::Value* specGloss = extension(kSpecGloss);
  MaterialDesc d;
  d.name = g.name.empty() ? where : g.name;
  d.albedo = factor3(pbr.baseColorFactor, 1.0);
  double strength = 1.0;
  bool unlit = false;
  for (const auto& ext : g.extensions) {
    if (ext.first == "KHR_materials_emissive_strength" && ext.second.Has("emissiveStrength"))
      strength = ext.second.Get("emissiveStrength").GetNumberAsDouble();
    else if (ext.first == "KHR_materials_unlit") unlit = true;
    else if (!gltfMaterialExtensionRead(ext.first))
      unused_.add("extension " + ext.first, where, "material extension '" + oneLine(ext.first, 60) + "' not used by montecl, ignored");
  }
  d.emission = factor3(g.emissiveFactor, strength);
  d.twoSidedEmission = g.doubleSided;
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(d.albedo[c]) || d.albedo[c] < 0) loadFail(file_, where, "baseColorFactor must be finite and >= 0");
    if (!std::isfinite(d.emission[c]) || d.emission[c] < 0) loadFail(file_, where, "emissiveFactor x emissiveStrength must be finite and >= 0");
  }
  const auto texture = [&](const auto& info, const char* key, TextureSampling& sampling) {
    return texturePath(i, info.index, info.texCoord, info.extensions, key, sampling);
  };
  // The base colour: pbrMetallicRoughness's, or the specular-glossiness diffuse (below).
  if (!specGloss && pbr.baseColorTexture.index >= 0)
    d.albedoTexture = texture(pbr.baseColorTexture, "pbrMetallicRoughness.baseColorTexture", d.albedoSampling);
  ExtTexture specGlossMap;  // KHR_materials_pbrSpecularGlossiness's specularGlossinessTexture
  MetalRoughFactors converted;
  // The base colour's alpha: baseColorFactor's, or the specular-glossiness diffuseFactor's.
  double alphaFactor = pbr.baseColorFactor.size() == 4 ? pbr.baseColorFactor[3] : 1.0;
  if (specGloss) {
    const std::string at = where + ".extensions." + kSpecGloss;
    const glm::vec4 diffuse = extColour(file_, at, *specGloss, "diffuseFactor", 4, glm::vec4(1.0f));
    const glm::vec3 specular = glm::vec3(extColour(file_, at, *specGloss, "specularFactor", 3, glm::vec4(1.0f)));
    const double gloss = extNumber(file_, at, *specGloss, "glossinessFactor", 1.0);
    if (!(gloss >= 0.0 && gloss <= 1.0)) loadFail(file_, at + ".glossinessFactor", "must be in [0, 1]");
    converted = metalRoughFromSpecGloss(glm::vec3(diffuse), specular, float(gloss));
    alphaFactor = diffuse.w;
    d.albedo = converted.base;
    const ExtTexture diffuseMap = extTexture(file_, at, *specGloss, "diffuseTexture");
    if (diffuseMap.index >= 0)
      d.albedoTexture = texturePath(i, diffuseMap.index, diffuseMap.texCoord, diffuseMap.extensions,
                                    std::string("extensions.") + kSpecGloss + ".diffuseTexture", d.albedoSampling);
    specGlossMap = extTexture(file_, at, *specGloss, "specularGlossinessTexture");
    if (specGlossMap.index >= 0) {  // per texel, converted by the texture loader (MaterialDesc::specGloss)
      d.specGlossMap = true;
      d.specGloss = glm::vec4(specular, float(gloss));
      d.specGlossDiffuse = glm::vec3(diffuse);
    }
    unused_.add("spec-gloss", where,
                std::string(kSpecGloss) + " converted to metallic-roughness on load: an approximation (exact for grey "
                "colours; a coloured specular keeps its brightness, not its hue" +
                (diffuseMap.index >= 0 && specGlossMap.index >= 0
                     ? "; per texel the diffuse texture is the base colour and the specular map's metallic assumes "
                       "the diffuseFactor's brightness)"
                     : ")"));
  }
  if (g.alphaMode == "MASK") {
    d.alphaCutoff = static_cast<float>(g.alphaCutoff);
    if (!(d.alphaCutoff >= 0.0f && d.alphaCutoff <= 1.0f)) loadFail(file_, where, "alphaCutoff must be in [0, 1]");
    d.alphaTexture = d.albedoTexture;
    d.alphaSampling = d.albedoSampling;
    if (d.alphaTexture.empty()) unused_.add("constant alpha", where, "alphaMode MASK without a usable base colour texture: no cut-out");
  } else if (g.alphaMode == "BLEND") {
    // Stochastic transparency (pbrt-v4's and Cycles' reading of alpha): a ray meets the surface
    // with probability baseColorFactor's alpha x the base colour texture's (the texture read as a
    // MASK cut-out reads it) and passes straight through otherwise, so a pixel sees
    // alpha x the surface + (1 - alpha) x what lies behind, shadows included.
    if (!(alphaFactor >= 0.0 && alphaFactor <= 1.0)) loadFail(file_, where, "the base colour's alpha must be in [0, 1]");
    d.alphaBlend = true;
    d.alphaFactor = static_cast<float>(alphaFactor);
    d.alphaTexture = d.albedoTexture;
    d.alphaSampling = d.albedoSampling;
  }
  // KHR_materials_unlit: the base colour is what the surface shows, lit or not: it becomes the
  // emission (Le = baseColorFactor x baseColorTexture, both faces when doubleSided) and the surface
  // reflects nothing (albedo 0, no other texture read).
  if (unlit) {
    d.emission = d.albedo;
    d.emissionTexture = d.albedoTexture;
    d.emissionSampling = d.albedoSampling;
    d.albedo = glm::vec3(0.0f);
    d.albedoTexture.clear();
    d.albedoSampling = TextureSampling{};
    return d;
  }
  // emissiveFactor x emissiveTexture (x strength); with a black factor the texture emits nothing:
  // not read at all.
  if (g.emissiveTexture.index >= 0 && d.emission != glm::vec3(0.0f))
    d.emissionTexture = texture(g.emissiveTexture, "emissiveTexture", d.emissionSampling);
  // metallic/roughness factors -> the metal_rough kind, glTF's defaults (1, 1) included (a rough
  // metal). The (0, 1) pair alone stays Lambertian: metal_rough is then nearly Lambert (a rough
  // dielectric with F0 0.04), and every such glTF material rendered so before the kind existed.
  const float metallic = specGloss ? converted.metallic : float(pbr.metallicFactor);
  const float roughness = specGloss ? converted.roughness : float(pbr.roughnessFactor);
  if (!(metallic >= 0.0f && metallic <= 1.0f)) loadFail(file_, where, "metallicFactor must be in [0, 1]");
  if (!(roughness >= 0.0f && roughness <= 1.0f)) loadFail(file_, where, "roughnessFactor must be in [0, 1]");
  // A metallicRoughnessTexture (B metallic, G roughness, x the factors) always means metal_rough.
  const bool mrTexture = !specGloss && pbr.metallicRoughnessTexture.index >= 0 && (metallic > 0.0f || roughness > 0.0f);
  const bool sgTexture = specGlossMap.index >= 0;
  d.kind = metallic == 0.0f && roughness == 1.0f && !mrTexture && !sgTexture ? MCL_MATERIAL_diffuse : MCL_MATERIAL_metal_rough;
  d.metallic = metallic;
  d.roughness = roughness;
  if (mrTexture)
    d.metallicRoughnessTexture = texture(pbr.metallicRoughnessTexture, "pbrMetallicRoughness.metallicRoughnessTexture",
                                         d.metallicRoughnessSampling);
  if (sgTexture) {  // its texels hold metallic (B) and roughness (G) once converted: the factors are 1
    d.metallicRoughnessTexture =
        texturePath(i, specGlossMap.index, specGlossMap.texCoord, specGlossMap.extensions,
                    std::string("extensions.") + kSpecGloss + ".specularGlossinessTexture", d.metallicRoughnessSampling);
    d.metallic = d.roughness = 1.0f;
    if (d.metallicRoughnessTexture.empty()) {  // missing (--missing-textures warn): the factors alone
      d.metallic = converted.metallic, d.roughness = converted.roughness;
      d.specGlossMap = false;
    }
  }
  if (g.normalTexture.index >= 0) {
    d.normalScale = static_cast<float>(g.normalTexture.scale);
    if (!std::isfinite(d.normalScale)) loadFail(file_, where, "normalTexture scale must be finite");
    d.normalTexture = texture(g.normalTexture, "normalTexture", d.normalSampling);
  }
  applyGltfSpecular(file_, where, extension(kSpecular), g, d, unused_);
  if (const tinygltf::Value* tr = extension("KHR_materials_transmission")) {  // R x the factor, per hit
    const std::string at = where + ".extensions.KHR_materials_transmission";
    const ExtTexture map = extTexture(file_, at, *tr, "transmissionTexture");
    if (map.index >= 0)
      d.transmissionTexture = texturePath(i, map.index, map.texCoord, map.extensions,
                                          "extensions.KHR_materials_transmission.transmissionTexture", d.transmissionSampling);
  }
  applyGltfTransmission(file_, where, g, d, unused_);
  applyGltfClearcoat(file_, where, g, d, unused_);
  applyGltfSheen(file_, where, g, d, unused_);
  if (g.occlusionTexture.index >= 0) unused_.add("occlusionTexture", where, "occlusionTexture not used by montecl, ignored");
  return d;
}

}  // namespace montecl
