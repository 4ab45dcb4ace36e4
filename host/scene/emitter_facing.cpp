// emitter_facing.cpp: emittersFaceAnything(): a cheap host test for the all-black direct render
// of emitters wound away from the scene (scene.h).
#include <algorithm>
#include <limits>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_instances.h"

namespace montecl {
namespace {

bool emits(const MaterialDesc& m) { return m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f; }

}  // namespace

bool emittersFaceAnything(const Scene& scene) {
  std::vector<const SceneTriangle*> lights;
  std::vector<glm::vec3> points;  // vertices of the non-emitting triangles
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  // Instanced triangles are in object space (and never emit): their placed boxes' corners stand for them.
  const std::vector<std::uint8_t> instanced = instancedTriangles(scene);
  for (const glm::vec3& v : instanceBoxCorners(scene)) {
    points.push_back(v);
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const SceneTriangle& t = scene.triangles[i];
    if (instanced[i]) continue;
    if (emits(scene.materials[t.material])) {
      lights.push_back(&t);
      continue;
    }
    for (const glm::vec3& v : t.v) {
      points.push_back(v);
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  }
  if (lights.empty() || points.empty()) return true;  // nothing to say: no emitter, or nothing to light
  // Exact (every vertex) while the work is small, else the bounding box's corners (which may say
  // "faces something" when nothing is there: the warning is then missed, never wrong).
  const bool exact = double(lights.size()) * double(points.size()) <= 2e7;
  std::vector<glm::vec3> corners;
  for (int c = 0; c < 8; ++c) corners.push_back({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
  const std::vector<glm::vec3>& test = exact ? points : corners;
  // In double and relative to the scene's own size: at a scale of 2^-30 the float cross product's
  // length and an absolute floor on the tolerance said "faces nothing" of a lit box.
  const double extent = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
  for (const SceneTriangle* t : lights) {
    const glm::dvec3 v0(t->v[0]);
    const glm::dvec3 n = glm::cross(glm::dvec3(t->v[1]) - v0, glm::dvec3(t->v[2]) - v0);
    const bool twoSided = scene.materials[t->material].twoSidedEmission;
    const double eps = 1e-6 * glm::length(n) * extent;
    for (const glm::vec3& p : test) {
      const double side = glm::dot(n, glm::dvec3(p) - v0);
      if (side > eps || (twoSided && side < -eps)) return true;
    }
  }
  return false;
}

}  // namespace montecl
