// lights_key.h: the scene file's "lights" key: a list of {"type": "point" | "spot" |
// "directional", ...} (docs/scene-format.md), parsed and checked into LightDesc.
#pragma once
#include <nlohmann/json.hpp>

#include <vector>

#include "scene/json_fields.h"
#include "scene/scene.h"

namespace montecl {

// Throws InputError "<file>: lights[i].<key>: <problem>"; unknown keys become warnings.
std::vector<LightDesc> parseLightsKey(const JsonCtx& ctx, const nlohmann::json& value);

}  // namespace montecl
