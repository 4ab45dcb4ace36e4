// builtin_scenes.cpp: the analytic scenes of builtin_scenes.h.
#include "scene/builtin_scenes.h"

#include <cmath>

namespace montecl {

void addQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, std::uint32_t material) {
  s.triangles.push_back({{a, b, c}, material});
  s.triangles.push_back({{a, c, d}, material});
}

void finishScene(Scene& s) {
  if (s.materials.empty()) s.materials.push_back(MaterialDesc{});
  s.boundsMin = glm::vec3(1e30f);
  s.boundsMax = glm::vec3(-1e30f);
  for (const auto& t : s.triangles)
    for (const auto& v : t.v) {
      s.boundsMin = glm::min(s.boundsMin, v);
      s.boundsMax = glm::max(s.boundsMax, v);
    }
}

void addUvSphere(Scene& s, glm::vec3 center, float radius, int rings, int segments, bool withNormals,
                 std::uint32_t material) {
  const auto dir = [&](int ring, int seg) {  // unit direction of vertex (ring, seg); ring 0: +y pole
    const double theta = M_PI * ring / rings, phi = 2.0 * M_PI * (seg % segments) / segments;
    return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                     float(-std::sin(theta) * std::sin(phi)));
  };
  const auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    SceneTriangle t{{center + radius * a, center + radius * b, center + radius * c}, material};
    if (withNormals) {
      t.n[0] = a;
      t.n[1] = b;
      t.n[2] = c;
      t.attributes = kHasNormals;
    }
    s.triangles.push_back(t);
  };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      const glm::vec3 a = dir(r, k), b = dir(r + 1, k), c = dir(r + 1, k + 1), d = dir(r, k + 1);
      if (r > 0) add(a, b, d);              // not at the top pole (a == d there)
      if (r < rings - 1) add(b, c, d);      // not at the bottom pole (b == c there)
    }
}

void addFloor(Scene& s, std::uint32_t material) {
  const float r = 1000.0f, dx = 43.0f;
  addQuad(s, {-r + dx, 0, -r}, {-r + dx, 0, r}, {r + dx, 0, r}, {r + dx, 0, -r}, material);
}

Scene floorScene(glm::vec3 at, float height, float fovY, int size, int spp) {
  Scene s;
  s.path = "<floor scene>";
  addFloor(s);
  s.camera.position = at + glm::vec3(0, height, 0);
  s.camera.target = at;
  s.camera.up = {0, 0, -1};
  s.camera.fovY = fovY;
  s.camera.width = s.camera.height = size;
  s.render.spp = spp;
  finishScene(s);
  return s;
}

Scene wallScene(int size, int spp) {
  Scene s = floorScene({-0.5f, 0.0f, 0.0f}, 0.5f, 40.0f, size, spp);
  s.path = "<wall scene>";
  const float r = 1000.0f;
  addQuad(s, {0, 0, -r}, {0, r, -r}, {0, r, r}, {0, 0, r});
  finishScene(s);
  return s;
}

}  // namespace montecl
