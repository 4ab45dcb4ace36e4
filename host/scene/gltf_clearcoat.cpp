// gltf_clearcoat.cpp: applyGltfClearcoat (gltf_clearcoat.h): reads a glTF material's
// KHR_materials_clearcoat object, writes the MaterialDesc's coat.
#include "scene/gltf_clearcoat.h"

namespace montecl {
namespace {

const char* const kClearcoat = "KHR_materials_clearcoat";

// ext[key]: a number in [0, 1], or fallback when absent.
float unitFactor(const std::string& file, const std::string& where, const tinygltf::Value& ext, const char* key,
                 float fallback) {
  if (!ext.IsObject() || !ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  const double x = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
  if (!(x >= 0.0 && x <= 1.0)) loadFail(file, where + ".extensions." + kClearcoat + "." + key, "must be a number in [0, 1]");
  return float(x);
}

}  // namespace

bool gltfClearcoatExtension(const std::string& name) { return name == kClearcoat; }

void applyGltfClearcoat(const std::string& file, const std::string& where, const tinygltf::Material& g,
                        MaterialDesc& d, KindWarnings& unused) {
  const auto it = g.extensions.find(kClearcoat);
  if (it == g.extensions.end()) return;
  const tinygltf::Value& ext = it->second;
  const float factor = unitFactor(file, where, ext, "clearcoatFactor", 0.0f);
  const float roughness = unitFactor(file, where, ext, "clearcoatRoughnessFactor", 0.0f);
  if (factor == 0.0f) return;  // the extension's "the whole clearcoat layer is disabled"
  if (d.kind == MCL_MATERIAL_dielectric || d.kind == MCL_MATERIAL_thin_dielectric) {
    unused.add("clearcoat on glass", where, std::string(kClearcoat) + " on a fully transmissive material not used (no coat on glass)");
    return;
  }
  if (d.kind == MCL_MATERIAL_diffuse) d.kind = MCL_MATERIAL_metal_rough;  // glTF's BRDF of these factors, coated
  d.clearcoat = factor;
  d.clearcoatRoughness = roughness;
  if (ext.IsObject() && (ext.Has("clearcoatTexture") || ext.Has("clearcoatRoughnessTexture")))
    unused.add("clearcoat textures", where, "clearcoatTexture and clearcoatRoughnessTexture not read by montecl (the factors alone are used)");
  // Without its own normal map glTF's coat follows the interpolated normal; montecl's follows the
  // base's shading normal, so a base normal map shows through the coat.
  if (ext.IsObject() && ext.Has("clearcoatNormalTexture"))
    unused.add("clearcoat normal", where, "clearcoatNormalTexture not read by montecl (the coat follows the base's shading normal)");
  else if (g.normalTexture.index >= 0)
    unused.add("clearcoat normal", where, "the coat follows the base's normalTexture in montecl (glTF's coat is not normal-mapped)");
  if (d.transmission > 0.0f)
    unused.add("clearcoat over transmission", where, "the coat covers the reflecting part only (the transmitted part is uncoated glass)");
  if (d.emission != glm::vec3(0.0f))
    unused.add("clearcoat emission", where, "emission under a coat is not darkened by the coat's Fresnel term in montecl");
}

}  // namespace montecl
