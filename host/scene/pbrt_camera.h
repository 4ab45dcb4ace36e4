// pbrt_camera.h: pbrt-v4's perspective camera (its world-to-camera CTM, fov on the shorter image
// axis, lens) as montecl's Camera. Reads the Camera directive's parameters; writes a Camera and
// the reflection of the world that makes montecl's right-handed camera show pbrt's picture.
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "scene/pbrt_params.h"
#include "scene/scene.h"

namespace montecl {

struct PbrtCamera {
  Camera camera;
  // pbrt's camera space is left-handed (x right, y up, z forward), montecl's image right is
  // cross(forward, up). When pbrt's camera-to-world keeps orientation (every LookAt camera), the
  // two disagree: the world is then reflected through the camera's vertical plane (the plane of
  // its view direction and up, through its position), which leaves the camera as it is and gives
  // pbrt's picture. Identity when they agree.
  glm::dmat4 worldMirror{1.0};
  bool mirrored = false;
};

// type: the Camera directive's type ("perspective"; others are rendered as perspective with a
// warning). cameraFromWorld: the CTM at the Camera directive. width, height: the film's.
PbrtCamera pbrtCamera(const std::string& type, const PbrtParams& params, const glm::dmat4& cameraFromWorld, int width,
                      int height, std::vector<std::string>& warnings);

}  // namespace montecl
