// texture_identity.h: what the texture budget did to a scene's textures, as text for the render
// identity (provenance and checkpoint key). Reads a SceneTextures; writes nothing.
#pragma once
#include <string>

#include "texture/scene_textures.h"

namespace montecl {

// "" when every texture kept all its mip levels (then the budget changed nothing, whatever it was),
// else "texture_levels_dropped=0,2,1": the finest levels each loaded texture lost. The effect, not
// the budget, is the identity: the automatic budget depends on the device, and two budgets that
// drop the same levels render the same image.
std::string textureBudgetIdentity(const SceneTextures& textures);

}  // namespace montecl
