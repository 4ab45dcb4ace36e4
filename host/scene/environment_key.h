// environment_key.h: the scene file's "environment" key: {"radiance": [r, g, b]} (constant) or
// {"file": "sky.exr", "scale": 1.0, "rotate_y": 0} (latitude-longitude map, rotate_y in degrees;
// "radiance" then tints the map). The map itself is read at render time
// (host/render/environment_table.cpp); here only that it is a readable file.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// Throws InputError "<sceneFile>: environment.<key>: <problem>"; unknown keys become warnings.
EnvironmentDesc parseEnvironmentKey(const std::string& sceneFile, const nlohmann::json& value,
                                    std::vector<std::string>& warnings);

}  // namespace montecl
