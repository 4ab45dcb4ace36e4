// device_materials.cpp: MaterialDesc -> Material (device_materials.h): reads the scene's materials
// (and texture indices), writes the device records.
#include "render/device_materials.h"

#include "kernels/shared/microfacet.h"

namespace montecl {

Material deviceMaterial(const MaterialDesc& m) {
  const float noTexture = glm::uintBitsToFloat(MCL_NO_TEXTURE);
  Material d{};
  d.albedo = glm::vec4(m.albedo, noTexture);
  d.emission = glm::vec4(m.emission, m.twoSidedEmission ? 1.0f : 0.0f);
  d.specular = glm::vec4(m.specular, ggx_alpha_from_ns(m.specularExponent));
  d.alpha = glm::vec4(noTexture, m.alphaCutoff, glm::uintBitsToFloat(0u), glm::uintBitsToFloat(m.kind));
  return d;
}

std::vector<Material> deviceMaterials(const std::vector<MaterialDesc>& materials, const SceneTextures* textures) {
  std::vector<Material> out;
  out.reserve(materials.size());
  for (const MaterialDesc& m : materials) out.push_back(deviceMaterial(m));
  if (textures) setTextureIndices(out, *textures);
  return out;
}

}  // namespace montecl
