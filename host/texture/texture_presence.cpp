// texture_presence.cpp: which texture slots a scene's materials fill (scene_textures.h:
// usesBumpMap, sceneHasTextures); reads the scene, writes nothing.
#include "texture/scene_textures.h"

namespace montecl {

bool usesBumpMap(const MaterialDesc& m) { return !m.bumpTexture.empty() && m.normalTexture.empty(); }

bool sceneHasTextures(const Scene& scene) {
  for (const MaterialDesc& m : scene.materials)
    if (!m.albedoTexture.empty() || !m.alphaTexture.empty() || !m.emissionTexture.empty() ||
        !m.metallicRoughnessTexture.empty() || !m.normalTexture.empty() || usesBumpMap(m) ||
        !m.transmissionTexture.empty())
      return true;
  return false;
}

}  // namespace montecl
