// mitsuba_scene.h: loadMitsubaScene(): a Mitsuba 3 scene file (.xml, with its <include>d files,
// OBJ/PLY meshes and bitmap textures) as montecl's Scene. Bad input: one InputError
// "<file>:<line>:<column>: <problem>"; what montecl leaves out: one warning each,
// "<file>:<line>:<column>: <what is left out>" (docs/mitsuba-format.md lists both).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

Scene loadMitsubaScene(const std::string& path, std::vector<std::string>& warnings,
                       std::optional<MissingTextures> missing = std::nullopt);

}  // namespace montecl
