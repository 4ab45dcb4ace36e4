// gltf_transmission.h: glTF's KHR_materials_transmission (+ KHR_materials_ior, KHR_materials_volume)
// onto montecl's material kinds: reads a glTF material's extension objects (and the
// transmissionTexture the material loader resolved into MaterialDesc::transmissionTexture), writes
// MaterialDesc's kind, ior, transmission, transmissionSolid and transmissionTinted (docs/scene-format.md, "glTF transmission").
#pragma once
#include <tiny_gltf.h>

#include <string>

#include "scene/load_util.h"
#include "scene/scene.h"

namespace montecl {

// True for the material extensions applyGltfTransmission reads.
bool gltfTransmissionExtension(const std::string& name);

// Applies g's transmission extensions to d, whose factors, base colour and textures the loader has
// already read (d.metallic, d.roughness: the (0, 1) pair the loader leaves diffuse counts as
// metallic 0). A transmission factor of 0 (or none) leaves d as it is. Factor 1 on a dielectric
// (metallic 0, no metallicRoughnessTexture nor transmissionTexture) makes d the kind dielectric (with KHR_materials_volume
// and thicknessFactor > 0; alpha = roughness^2) or thin_dielectric (without); any other factor
// keeps metal_rough and records the factor for the per-hit choice of kernels/shared/
// transmission_mix.h; either way the base colour tints the transmitted light (transmissionTinted,
// kernels/shared/transmission_tint.h). Throws InputError "<file>: <where>.extensions.<ext>.<key>:
// <problem>" for a factor outside [0, 1], an ior below 1 (other than 0) or not finite, a negative
// thicknessFactor, a non-number; what it does not model (attenuation, ior 0, roughness of a
// thin sheet) is one warning per kind through unused.
void applyGltfTransmission(const std::string& file, const std::string& where, const tinygltf::Material& g,
                           MaterialDesc& d, KindWarnings& unused);

}  // namespace montecl
