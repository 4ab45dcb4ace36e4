// pbrt_materials.h: pbrt-v4 textures and materials as montecl's: Texture directives (imagemap,
// constant, scale, checkerboard, mix) and Material / MakeNamedMaterial types as the nearest
// montecl material kind. Reads the directives' parameters; writes MaterialDesc values. What
// montecl cannot show (coatings, procedural textures, anisotropy) is one warning each.
#pragma once
#include <glm/glm.hpp>

#include <map>
#include <string>
#include <vector>

#include "scene/pbrt_params.h"
#include "scene/scene.h"

namespace montecl {

// A texture as far as montecl can read it: an image file times a colour, or a colour alone.
struct PbrtTexture {
  std::string file;        // image (resolved path), "" for a constant
  glm::vec3 value{1.0f};   // the colour (multiplies the image)
  TextureSampling sampling;
  bool exact = true;       // false: an approximation (warned about when the texture was made)
};
using PbrtTextures = std::map<std::string, PbrtTexture>;

// Texture "name" "spectrum"|"float" "<klass>" params. baseFile: the main scene file, whose folder resolves file names (as pbrt does).
// Records texture t's file among the scene's inputs, or, when it cannot be opened, as a missing
// texture at its "filename" parameter (the texture is then left without a file).
void notePbrtTextureFile(Scene& scene, PbrtTexture& t, const PbrtParams& p);

PbrtTexture pbrtTexture(const std::string& klass, const PbrtParams& params, const PbrtTextures& known,
                        const std::string& baseFile, std::vector<std::string>& warnings);

// A material of pbrt type `type` (the Material directive's, or MakeNamedMaterial's "string type").
// named: the named materials so far (for mix); baseFile: the main scene file, whose folder resolves file names (as pbrt does) (normal maps).
MaterialDesc pbrtMaterial(const std::string& type, const PbrtParams& params, const PbrtTextures& textures,
                          const std::map<std::string, MaterialDesc>& named, const std::string& baseFile,
                          std::vector<std::string>& warnings);

}  // namespace montecl
