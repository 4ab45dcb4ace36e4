// pbrt_lights.h: pbrt-v4's LightSource directive (point, spot, distant, infinite) as montecl's
// punctual lights and environment. Reads the directive's parameters and its placement; writes
// Scene::lights and Scene::environment. Other light types are one warning each.
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "scene/pbrt_params.h"
#include "scene/scene.h"

namespace montecl {

// toWorld: the light's CTM (with the world's mirror, pbrt_camera.h). baseFile resolves file names.
void pbrtLightSource(const std::string& type, const PbrtParams& params, const glm::dmat4& toWorld,
                     const std::string& baseFile, Scene& scene, std::vector<std::string>& warnings);

}  // namespace montecl
