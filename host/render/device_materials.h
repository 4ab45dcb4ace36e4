// device_materials.h: the one packer of scene materials (MaterialDesc) into the device's Material
// records (kernels/shared/types.h) that every stage and the alpha test read.
#pragma once
#include <vector>

#include "kernels/shared/types.h"
#include "scene/scene.h"
#include "texture/scene_textures.h"

namespace montecl {

// One material: Kd, Ke (w: two-sided), Ks with the GGX alpha from Ns, the alpha cutoff, the kind
// tag (alpha.w as uint bits); no textures (MCL_NO_TEXTURE).
Material deviceMaterial(const MaterialDesc& m);

// Every material in order, with the texture indices of `textures` when given (setTextureIndices).
std::vector<Material> deviceMaterials(const std::vector<MaterialDesc>& materials,
                                      const SceneTextures* textures = nullptr);

}  // namespace montecl
