// layered_scene.cpp: builds the conformance set's layered-kinds scene (layered_scene.h) from the
// rough-glass scene's geometry.
#include "conformance/layered_scene.h"

#include "scene/builtin_scenes.h"

namespace montecl {

Scene layeredScene(const Scene& base) {
  Scene coated = base;
  coated.path = "<coated scene>";
  MaterialDesc& gold = coated.materials.back();
  gold.kind = MCL_MATERIAL_coated_conductor;
  gold.eta = {0.18f, 0.42f, 1.37f};
  gold.k = {3.42f, 2.35f, 1.77f};
  gold.baseAlpha = 0.2f;
  gold.kindAlpha = 0.05f;
  gold.thickness = 0.05f;
  gold.layerSamples = 2;
  MaterialDesc& layered = coated.materials[2];
  layered = MaterialDesc{"coated diffuse", glm::vec3(0.2f, 0.5f, 0.3f), glm::vec3(0.0f)};
  layered.kind = MCL_MATERIAL_coated_diffuse;
  layered.kindAlpha = 0.1f;
  finishScene(coated);
  return coated;
}

}  // namespace montecl
