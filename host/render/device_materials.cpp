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
  // alpha.y: a cut-out's cutoff (sign bit clear: -0 becomes 0), or stochastic transparency's alpha
  // factor negated (sign bit set, 0 included as -0; surface_texture.h alpha_hit_exists).
  const float alphaY = m.alphaBlend ? -m.alphaFactor : (m.alphaCutoff > 0.0f ? m.alphaCutoff : 0.0f);
  d.alpha = glm::vec4(noTexture, alphaY, glm::uintBitsToFloat(0u), glm::uintBitsToFloat(m.kind));
  d.maps = glm::vec4(noTexture, noTexture, 0.0f, 0.0f);
  // The kinds' parameters, as bsdf_<kind>.h's <kind>_from_material reads them; zero for diffuse.
  switch (m.kind) {
    case MCL_MATERIAL_conductor:
      d.params0 = glm::vec4(m.eta, m.kindAlpha);
      d.params1 = glm::vec4(m.k, m.beckmann ? 1.0f : 0.0f);
      d.specular = glm::vec4(m.conductorFactor, 0.0f);  // bsdf_conductor.h: the factor on F
      break;
    // z: 1 where the albedo tints the transmitted light (transmission_tint.h)
    case MCL_MATERIAL_dielectric: d.params0 = glm::vec4(m.ior, m.kindAlpha, m.transmissionTinted ? 1.0f : 0.0f, 0.0f); break;
    case MCL_MATERIAL_thin_dielectric: d.params0 = glm::vec4(m.ior, 0.0f, m.transmissionTinted ? 1.0f : 0.0f, 0.0f); break;
    case MCL_MATERIAL_metal_rough:
      // bsdf_metal_rough.h: the coat in specular.x, .y; the sheen's colour in params0.z, .w and
      // specular.z, its roughness in specular.w (slots no other reader of metal_rough uses: the
      // transmission pick rewrites params0.z only for the glass it picks)
      d.params0 = glm::vec4(m.metallic, m.roughness, m.sheenColor.x, m.sheenColor.y);
      d.specular = glm::vec4(m.clearcoat, m.clearcoatRoughness, m.sheenColor.z, m.sheenRoughness);
      // transmission_mix.h: x the factor, y the ior, z 1 for a solid dielectric (all 0 without);
      // w the transmission texture + 1 (setTextureIndices), 0 none
      if (m.transmission > 0.0f) d.params1 = glm::vec4(m.transmission, m.ior, m.transmissionSolid ? 1.0f : 0.0f, 0.0f);
      break;
    case MCL_MATERIAL_coated_diffuse:
      d.params0 = glm::vec4(m.kindAlpha, m.ior, m.thickness, 0.0f);
      d.params1 = glm::vec4(glm::uintBitsToFloat(std::uint32_t(m.layerMaxDepth)),
                            glm::uintBitsToFloat(std::uint32_t(m.layerSamples)), 0.0f, 0.0f);
      break;
    case MCL_MATERIAL_coated_conductor:  // bsdf_coated_conductor.h: the coat and layer in specular
      d.params0 = glm::vec4(m.eta, m.baseAlpha);
      d.params1 = glm::vec4(m.k, m.kindAlpha);
      d.specular = glm::vec4(m.ior, m.thickness, glm::uintBitsToFloat(std::uint32_t(m.layerMaxDepth)),
                             glm::uintBitsToFloat(std::uint32_t(m.layerSamples)));
      break;
    default: break;
  }
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
