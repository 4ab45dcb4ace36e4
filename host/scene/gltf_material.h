// gltf_material.h: glTF 2.0 materials onto montecl's MaterialDesc (docs/scene-format.md, "glTF
// materials"): reads a model's materials[] (factors, textures, alphaMode, the material extensions
// montecl reads), writes Scene::materials (one entry per glTF material used, made on first use)
// and the textures' image paths (Scene::inputFiles, Scene::embeddedImages, missing textures).
// - pbrMetallicRoughness: baseColor -> albedo (x baseColorTexture); metallic/roughness -> the
//   metal_rough kind (x metallicRoughnessTexture), glTF's defaults (1, 1) included: a rough metal, as
//   the specification defines them; only the (0, 1) pair stays Lambertian (metal_rough's rough
//   dielectric nearly is). A primitive without a material gets glTF's default material (white,
//   metallic 1, roughness 1), not montecl's grey Lambert.
// - KHR_materials_pbrSpecularGlossiness: converted to metal/rough on load (gltf_spec_gloss.h; an
//   approximation, warned); KHR_materials_specular where it maps onto a kind (specularFactor 0 on a
//   dielectric: Lambert), else warned; emission x KHR_materials_emissive_strength; unlit;
//   transmission (+ ior, volume: gltf_transmission.h); clearcoat (metal_rough's coat: gltf_clearcoat.h);
//   sheen (metal_rough's sheen: gltf_sheen.h).
#pragma once
#include <tiny_gltf.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "scene/load_util.h"
#include "scene/scene.h"

namespace montecl {

// True for the material extensions GltfMaterials reads (the others are warned as ignored).
bool gltfMaterialExtensionRead(const std::string& name);

class GltfMaterials {
 public:
  GltfMaterials(const std::string& file, const tinygltf::Model& m, Scene& scene, KindWarnings& unused);
  // The scene material of glTF material `index` (out of range: glTF's default material), made on
  // first use. Throws InputError "<file>: materials[i]...: <problem>" for a bad value.
  std::uint32_t index(int material);
  // The TEXCOORD_n set material's textures read (0 when it names none), and the key that named it.
  int uvSet(int material) const;
  const std::string& uvSetKey(int material) const;

 private:
  MaterialDesc read(std::size_t i);
  // The image path of a texture of material i (key names it in messages), checked now when it is a
  // file of its own; "" when it is missing and the render goes without it. Sets its sampling.
  std::string texturePath(std::size_t i, int texture, int texCoord, const tinygltf::ExtensionMap& extensions,
                          const std::string& key, TextureSampling& sampling);

  const std::string& file_;
  const tinygltf::Model& m_;
  Scene& scene_;
  KindWarnings& unused_;
  std::vector<std::int64_t> made_;  // glTF material -> scene material (-1: not yet)
  std::int64_t default_ = -1;       // glTF's default material, once made
  std::vector<int> uvSet_;
  std::vector<std::string> uvSetKey_;
  std::set<int> missingImages_;  // images whose file cannot be opened (recorded once each)
};

}  // namespace montecl
