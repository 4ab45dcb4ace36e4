// gltf_sheen.h: glTF's KHR_materials_sheen onto the metal_rough kind's sheen: reads a glTF
// material's extension object, writes MaterialDesc's kind, sheenColor and sheenRoughness
// (docs/scene-format.md, "glTF sheen").
#pragma once
#include <tiny_gltf.h>

#include <string>

#include "scene/load_util.h"
#include "scene/scene.h"

namespace montecl {

// True for the material extension applyGltfSheen reads.
bool gltfSheenExtension(const std::string& name);

// Applies g's KHR_materials_sheen to d, whose factors, textures, transmission and coat the loader
// has already read. A sheenColorFactor of 0 (the default, or no extension) leaves d as it is
// ("the whole sheen layer is disabled"); otherwise the layer is metal_rough's sheen (a diffuse d,
// the (0, 1) pair, becomes metal_rough with those factors, which glTF means anyway). Throws
// InputError "<file>: <where>.extensions.KHR_materials_sheen.<key>: <problem>" for a colour that is
// not 3 numbers in [0, 1] or a roughness outside [0, 1]; what it does not model (the two textures,
// a sheen on glass) is one warning per kind through unused.
void applyGltfSheen(const std::string& file, const std::string& where, const tinygltf::Material& g, MaterialDesc& d,
                    KindWarnings& unused);

}  // namespace montecl
