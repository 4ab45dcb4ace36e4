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

// The environment of the command line: --env "R,G,B" (a constant radiance), "none" (disabled) or a
// map file (resolved against the working folder), times --env-scale, rotated by --env-rotate degrees about +y.
// Throws InputError "--env: <problem>" (or "--env-scale: ...").
EnvironmentDesc environmentFromOption(const std::string& env, float scale, float rotateYDegrees);

}  // namespace montecl
