// default_camera.cpp: frames a bounding box for scenes given as a bare OBJ: the camera looks at the
// box centre from the +z side, tilted down a little, at the smallest distance at which all eight
// corners project inside the image (with a small margin), for the image's aspect ratio.
#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace montecl {
namespace {

constexpr double kDefaultFovY = 40.0;  // degrees
constexpr double kMargin = 1.05;       // corners stay this factor inside the image edges

struct Basis {
  glm::dvec3 right, up, forward;
};

Basis viewBasis() {
  Basis b;
  b.forward = glm::normalize(glm::dvec3(0.0, -0.25, -1.0));  // toward -z, ~14 degrees down
  b.right = glm::normalize(glm::cross(b.forward, glm::dvec3(0.0, 1.0, 0.0)));
  b.up = glm::cross(b.right, b.forward);
  return b;
}

// Smallest distance back from the centre along -forward at which every corner is in the view.
double framingDistance(const glm::dvec3& lo, const glm::dvec3& hi, const Basis& b, double tanX, double tanY) {
  glm::dvec3 center = 0.5 * (lo + hi);
  double distance = 0.0;
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    glm::dvec3 d = p - center;
    double depth = glm::dot(d, b.forward);  // corner depth is distance + depth
    distance = std::max(distance, std::abs(glm::dot(d, b.right)) / tanX - depth);
    distance = std::max(distance, std::abs(glm::dot(d, b.up)) / tanY - depth);
  }
  double radius = 0.5 * glm::length(hi - lo);
  return std::max(distance, 1e-3 * radius);  // never at the centre of a flat box
}

}  // namespace

Camera defaultCamera(const glm::vec3& boundsMin, const glm::vec3& boundsMax, int width, int height) {
  glm::dvec3 lo(boundsMin), hi(boundsMax);
  double aspect = static_cast<double>(std::max(width, 1)) / std::max(height, 1);
  double tanY = std::tan(0.5 * kDefaultFovY * M_PI / 180.0) / kMargin;
  double tanX = tanY * aspect;
  Basis b = viewBasis();
  double distance = framingDistance(lo, hi, b, tanX, tanY);
  if (!(distance > 0.0) || !std::isfinite(distance)) distance = 1.0;
  glm::dvec3 center = 0.5 * (lo + hi);

  Camera cam;
  cam.target = glm::vec3(center);
  cam.position = glm::vec3(center - b.forward * distance);
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  cam.fovY = static_cast<float>(kDefaultFovY);
  cam.width = width;
  cam.height = height;
  return cam;
}

}  // namespace montecl
