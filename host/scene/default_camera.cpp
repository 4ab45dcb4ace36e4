// default_camera.cpp: frames a bounding box for scenes given as a bare mesh (or with --view): the
// camera looks at the box centre from one side (front: the +z side, tilted down a little), at the
// smallest distance at which all eight corners project inside the image (with a small margin), for
// the image's aspect ratio.
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

// The sides a model can be seen from: the direction the camera looks along, and its up hint.
struct ViewSide {
  const char* name;
  glm::dvec3 forward, up;
};
constexpr ViewSide kSides[] = {
    {"front", {0.0, -0.25, -1.0}, {0.0, 1.0, 0.0}},  {"back", {0.0, -0.25, 1.0}, {0.0, 1.0, 0.0}},
    {"left", {1.0, -0.25, 0.0}, {0.0, 1.0, 0.0}},    {"right", {-1.0, -0.25, 0.0}, {0.0, 1.0, 0.0}},
    {"top", {0.0, -1.0, 0.0}, {0.0, 0.0, -1.0}},     {"bottom", {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}},
    {"iso", {-1.0, -0.8, -1.0}, {0.0, 1.0, 0.0}}};

Basis viewBasis(const ViewSide& side) {
  Basis b;
  b.forward = glm::normalize(side.forward);  // front: toward -z, ~14 degrees down
  b.right = glm::normalize(glm::cross(b.forward, side.up));
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

const char* viewNames() { return "front, back, left, right, top, bottom, iso"; }

bool isViewName(const std::string& view) {
  for (const ViewSide& s : kSides)
    if (view == s.name) return true;
  return false;
}

Camera defaultCamera(const glm::vec3& boundsMin, const glm::vec3& boundsMax, int width, int height,
                     const std::string& view) {
  const ViewSide* side = &kSides[0];
  for (const ViewSide& s : kSides)
    if (view == s.name) side = &s;
  glm::dvec3 lo(boundsMin), hi(boundsMax);
  double aspect = static_cast<double>(std::max(width, 1)) / std::max(height, 1);
  double tanY = std::tan(0.5 * kDefaultFovY * M_PI / 180.0) / kMargin;
  double tanX = tanY * aspect;
  Basis b = viewBasis(*side);
  double distance = framingDistance(lo, hi, b, tanX, tanY);
  if (!(distance > 0.0) || !std::isfinite(distance)) distance = 1.0;
  glm::dvec3 center = 0.5 * (lo + hi);

  Camera cam;
  cam.target = glm::vec3(center);
  cam.position = glm::vec3(center - b.forward * distance);
  cam.up = glm::vec3(side->up);
  cam.fovY = static_cast<float>(kDefaultFovY);
  cam.width = width;
  cam.height = height;
  return cam;
}

}  // namespace montecl
