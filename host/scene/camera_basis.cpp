// camera_basis.cpp: the float camera basis and its validation (see camera_basis.h). The basis is
// checked, not repaired: forward, right and up finite and orthonormal within 1e-3, the pixel steps
// finite and non-zero. In float, |target - position| above ~1.8e19 overflows the squared length
// (forward becomes 0, then NaN); below ~1e-19 it underflows (NaN); an `up` whose cross product with
// forward is tiny (1e-30, a denormal) underflows the same way.
#include "scene/camera_basis.h"

#include <cmath>
#include <sstream>

namespace montecl {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool unit(const glm::vec3& v) { return finite(v) && std::abs(glm::length(v) - 1.0f) < 1e-3f; }

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

CameraBasis cameraBasis(const Camera& camera) {
  CameraBasis b;
  b.forward = glm::normalize(camera.target - camera.position);
  b.right = glm::normalize(glm::cross(b.forward, camera.up));
  b.up = glm::cross(b.right, b.forward);
  float tanHalf = std::tan(glm::radians(camera.fovY) * 0.5f);
  float aspect = float(camera.width) / float(camera.height);
  b.topLeft = b.forward - b.right * (tanHalf * aspect) + b.up * tanHalf;
  b.dx = b.right * (2.0f * tanHalf * aspect / float(camera.width));
  b.dy = -b.up * (2.0f * tanHalf / float(camera.height));
  return b;
}

CameraProblem cameraBasisProblem(const Camera& camera) {
  const char* precision = " for float precision";
  if (!finite(camera.position)) return {"camera.position", "must be finite"};
  if (!finite(camera.target)) return {"camera.target", "must be finite"};
  if (!finite(camera.up)) return {"camera.up", "must be finite"};
  if (!(camera.fovY > 0.0f && camera.fovY < 180.0f)) return {"camera.fov_y", "must be in (0, 180) degrees"};
  const glm::vec3 dir = camera.target - camera.position;
  if (dir == glm::vec3(0.0f)) return {"camera.target", "equals camera.position (no view direction)"};
  if (camera.up == glm::vec3(0.0f)) return {"camera.up", "must not be the zero vector"};
  const glm::dvec3 d = glm::normalize(glm::dvec3(dir)), u = glm::normalize(glm::dvec3(camera.up));
  if (glm::length(glm::cross(d, u)) < 1e-5) return {"camera.up", "parallel to the view direction"};
  const CameraBasis b = cameraBasis(camera);
  if (!unit(b.forward)) {
    const double distance = glm::length(glm::dvec3(camera.target) - glm::dvec3(camera.position));
    if (distance >= 1.0)
      return {"camera.position", num(distance) + " from camera.target: too far" + std::string(precision)};
    return {"camera.target", num(distance) + " from camera.position: too close" + std::string(precision)};
  }
  if (!unit(b.right) || !unit(b.up) || std::abs(glm::dot(b.forward, b.right)) > 1e-3f ||
      std::abs(glm::dot(b.forward, b.up)) > 1e-3f || std::abs(glm::dot(b.right, b.up)) > 1e-3f)
    return {"camera.up", "too small, too large or too close to the view direction" + std::string(precision)};
  if (!finite(b.topLeft) || !finite(b.dx) || !finite(b.dy) || b.dx == glm::vec3(0.0f) || b.dy == glm::vec3(0.0f))
    return {"camera.fov_y", "gives degenerate pixel steps" + std::string(precision)};
  return {};
}

glm::dmat4 reflectionThroughPlane(const glm::dvec3& n, const glm::dvec3& p) {
  glm::dmat4 s(1.0);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) s[c][r] = (r == c ? 1.0 : 0.0) - 2.0 * n[r] * n[c];
  s[3] = glm::dvec4(2.0 * n * glm::dot(n, p), 1.0);
  return s;
}

}  // namespace montecl
