// default_camera.cpp: frames a bounding box for scenes given as a bare OBJ: the camera looks at the
// box centre from the +z side, tilted down a little, far enough back that the box's bounding
// sphere (and so every corner) fits inside both the vertical and horizontal field of view.
#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace montecl {
namespace {

constexpr float kDefaultFovY = 40.0f;  // degrees
constexpr float kMargin = 1.05f;       // a little space around the bounding sphere

// Half of the narrower of the vertical and horizontal fields of view, radians.
double narrowHalfAngle(float fovYDegrees, int width, int height) {
  double halfY = 0.5 * fovYDegrees * M_PI / 180.0;
  double aspect = static_cast<double>(std::max(width, 1)) / std::max(height, 1);
  double halfX = std::atan(std::tan(halfY) * aspect);
  return std::min(halfX, halfY);
}

}  // namespace

Camera defaultCamera(const glm::vec3& boundsMin, const glm::vec3& boundsMax, int width, int height) {
  glm::dvec3 lo(boundsMin), hi(boundsMax);
  glm::dvec3 center = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  if (!(radius > 0.0) || !std::isfinite(radius)) radius = 1.0;
  double distance = kMargin * radius / std::sin(narrowHalfAngle(kDefaultFovY, width, height));
  glm::dvec3 viewDir = glm::normalize(glm::dvec3(0.0, -0.25, -1.0));  // toward -z, ~14 deg down

  Camera cam;
  cam.target = glm::vec3(center);
  cam.position = glm::vec3(center - viewDir * distance);
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  cam.fovY = kDefaultFovY;
  cam.width = width;
  cam.height = height;
  return cam;
}

}  // namespace montecl
