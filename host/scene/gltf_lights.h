// gltf_lights.h: glTF's KHR_lights_punctual onto montecl's lights (scene.h LightDesc): point, spot
// (innerConeAngle -> beam width, outerConeAngle -> cutoff) and directional, placed by their node
// (position at its origin, shining down its -z). Units 1:1, as the Khronos sample viewer and
// three.js light a glTF: intensity in candela is taken as W/sr, lux as W/m^2 (no 683 lm/W), so a
// model looks as in those viewers.
#pragma once
#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <string>

#include "scene/load_util.h"
#include "scene/scene.h"

namespace montecl {

// The KHR_lights_punctual light a node carries, or -1.
int gltfNodeLight(const tinygltf::Node& node);

// Appends light `index` of m, placed by the node transform `world`, to scene.lights. Throws
// InputError "<file>: KHR_lights_punctual.lights[i].<key>: <problem>" for an out-of-range index,
// an unknown type, a negative or non-finite colour or intensity, or bad cone angles; a `range`
// is warned once through unused (montecl's lights fall off as 1/d^2 without a cut-off).
void addGltfLight(const std::string& file, const tinygltf::Model& m, int index, const glm::dmat4& world, Scene& scene,
                  KindWarnings& unused);

}  // namespace montecl
