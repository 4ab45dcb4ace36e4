// texture_identity.cpp: the texture budget's part of the render identity (texture_identity.h).
// Reads a SceneTextures; writes nothing.
#include "texture/texture_identity.h"

namespace montecl {

std::string textureBudgetIdentity(const SceneTextures& textures) {
  bool any = false;
  std::string list;
  for (const TextureDesc& d : textures.textures) {
    any = any || d.dropped != 0;
    list += (list.empty() ? "" : ",") + std::to_string(d.dropped);
  }
  return any ? "texture_levels_dropped=" + list : std::string();
}

}  // namespace montecl
