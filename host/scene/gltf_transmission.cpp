// gltf_transmission.cpp: applyGltfTransmission (gltf_transmission.h): reads a glTF material's
// KHR_materials_transmission / _ior / _volume objects, writes the MaterialDesc's transmission.
#include "scene/gltf_transmission.h"

#include <cmath>

namespace montecl {
namespace {

const char* const kTransmission = "KHR_materials_transmission";
const char* const kIor = "KHR_materials_ior";
const char* const kVolume = "KHR_materials_volume";

const tinygltf::Value* extension(const tinygltf::Material& g, const char* name) {
  const auto it = g.extensions.find(name);
  return it == g.extensions.end() ? nullptr : &it->second;
}

// ext[key] as a finite number, or fallback when ext has no such key.
double number(const std::string& file, const std::string& where, const tinygltf::Value* ext, const char* name,
              const char* key, double fallback) {
  if (!ext || !ext->IsObject() || !ext->Has(key)) return fallback;
  const tinygltf::Value& v = ext->Get(key);
  const std::string at = where + ".extensions." + name + "." + key;
  if (!v.IsNumber()) loadFail(file, at, "must be a number");
  const double x = v.GetNumberAsDouble();
  if (!std::isfinite(x)) loadFail(file, at, "must be finite");
  return x;
}

}  // namespace

bool gltfTransmissionExtension(const std::string& name) { return name == kTransmission || name == kIor || name == kVolume; }

void applyGltfTransmission(const std::string& file, const std::string& where, const tinygltf::Material& g,
                           MaterialDesc& d, KindWarnings& unused) {
  const tinygltf::Value* tr = extension(g, kTransmission);
  const tinygltf::Value* io = extension(g, kIor);
  const tinygltf::Value* vol = extension(g, kVolume);
  const double t = number(file, where, tr, kTransmission, "transmissionFactor", 0.0);
  if (!(t >= 0.0 && t <= 1.0)) loadFail(file, where + ".extensions." + kTransmission + ".transmissionFactor", "must be in [0, 1]");
  double ior = number(file, where, io, kIor, "ior", 1.5);
  // The extension allows 0: the specular-glossiness compatibility mode, an infinite index (Fresnel 1).
  if (ior == 0.0) {
    unused.add("ior 0", where, "KHR_materials_ior ior 0 (an infinite index: the specular-glossiness compatibility mode) not supported, 1.5 used");
    ior = 1.5;
  }
  if (!(ior >= 1.0)) loadFail(file, where + ".extensions." + kIor + ".ior", "must be >= 1 (or 0)");
  const double thickness = number(file, where, vol, kVolume, "thicknessFactor", 0.0);
  if (!(thickness >= 0.0)) loadFail(file, where + ".extensions." + kVolume + ".thicknessFactor", "must be >= 0");
  if (t == 0.0) {  // no transmission: what the other two would change is not modelled
    d.transmissionTexture.clear();  // (it scales a factor of 0)
    d.transmissionSampling = TextureSampling{};
    if (io && ior != 1.5)
      unused.add("ior without transmission", where, "KHR_materials_ior without transmission not used (metal_rough's F0 stays 0.04)");
    if (vol) unused.add("volume without transmission", where, "KHR_materials_volume without transmission not used");
    return;
  }
  if (vol && vol->IsObject() && (vol->Has("attenuationDistance") || vol->Has("attenuationColor") || vol->Has("thicknessTexture")))
    unused.add("attenuation", where, "KHR_materials_volume attenuation and thicknessTexture not used (a clear interior)");
  // glTF: thicknessFactor 0 (the default) is a thin-walled material, > 0 the boundary of a volume.
  const bool solid = thickness > 0.0;
  // The factors as the loader read them into d (gltf_material.cpp): glTF's defaults (1, 1) are a
  // rough metal, through which nothing is transmitted (p = t (1 - metallic) = 0), as glTF defines.
  const float metallic = d.metallic, roughness = d.roughness;
  if (!solid && roughness > 0.0f)
    unused.add("thin roughness", where, "the roughness of a thin-walled transmission not used (montecl's thin sheet is smooth)");
  d.ior = float(ior);
  d.transmissionTinted = true;  // glTF's BTDF x the base colour (x its texture x COLOR_0)
  if (t == 1.0 && metallic == 0.0f && d.metallicRoughnessTexture.empty() && d.transmissionTexture.empty()) {
    // All of it transmits through a dielectric: exactly the kind (the scene file's equivalent).
    d.kind = solid ? MCL_MATERIAL_dielectric : MCL_MATERIAL_thin_dielectric;
    d.kindAlpha = solid ? roughness * roughness : 0.0f;
    d.roughness = roughness;
    return;
  }
  d.kind = MCL_MATERIAL_metal_rough;
  d.metallic = metallic;
  d.roughness = roughness;
  d.transmission = float(t);
  d.transmissionSolid = solid;
}

}  // namespace montecl
