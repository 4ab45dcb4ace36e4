// gltf_clearcoat.h: glTF's KHR_materials_clearcoat onto the metal_rough kind's coat: reads a glTF
// material's extension object, writes MaterialDesc's kind, clearcoat and clearcoatRoughness
// (docs/scene-format.md, "glTF clearcoat").
#pragma once
#include <tiny_gltf.h>

#include <string>

#include "scene/load_util.h"
#include "scene/scene.h"

namespace montecl {

// True for the material extension applyGltfClearcoat reads.
bool gltfClearcoatExtension(const std::string& name);

// Applies g's KHR_materials_clearcoat to d, whose factors, textures and transmission the loader has
// already read. clearcoatFactor 0 (or no extension) leaves d as it is; otherwise the layer is
// metal_rough's coat (a diffuse d, the (0, 1) pair, becomes metal_rough with those factors, which
// glTF means anyway). Throws InputError "<file>: <where>.extensions.KHR_materials_clearcoat.<key>:
// <problem>" for a factor outside [0, 1] or not a number; what it does not model (the coat's
// textures and normal map, the coat over glass, emission under the coat) is one warning per kind
// through unused.
void applyGltfClearcoat(const std::string& file, const std::string& where, const tinygltf::Material& g,
                        MaterialDesc& d, KindWarnings& unused);

}  // namespace montecl
