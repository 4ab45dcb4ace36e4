// pbrt_scene.h: loadPbrtScene(): a pbrt-v4 scene file (.pbrt, with its Includes, PLY meshes and
// textures) as montecl's Scene. Bad input: one InputError "<file>:<line>:<column>: <problem>";
// what montecl leaves out: one warning each, "<file>:<line>:<column>: <what is left out>".
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

Scene loadPbrtScene(const std::string& path, std::vector<std::string>& warnings,
                    std::optional<MissingTextures> missing = std::nullopt);

// Whether path names a pbrt-v4 scene file (extension .pbrt, any case).
bool isPbrtScenePath(const std::string& path);

}  // namespace montecl
