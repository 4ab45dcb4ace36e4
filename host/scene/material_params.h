// material_params.h: the material kinds' own scene-file keys (eta, k, metal, alpha, roughness,
// ior, metallic): parsed and validated into MaterialDesc's kind parameters.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "scene/json_fields.h"
#include "scene/scene.h"

namespace montecl {

// Reads the kind-parameter keys of material object j (key path prefix) into d. d.kind must already
// hold the entry's type. Fails (one line, naming the key) on a value out of range, an unknown metal,
// "alpha" together with "roughness", or "eta"/"k" together with "metal". True when any key was given.
bool parseKindParams(const JsonCtx& ctx, const nlohmann::json& j, const std::string& prefix, MaterialDesc& d);

// The RGB complex IOR of a named metal ("Au", "Ag", "Cu", "Al", "Cr"); false for another name.
bool metalEtaK(const std::string& name, glm::vec3& eta, glm::vec3& k);

}  // namespace montecl
