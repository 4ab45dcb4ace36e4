// test_scenes.h: small scenes built in code for the render tests: quads, an open plane, a wall.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace montecl_test {

// Appends the quad a, b, c, d (counter-clockwise seen from its front) as two triangles.
inline void addQuad(montecl::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d,
                    std::uint32_t material = 0) {
  s.triangles.push_back({{a, b, c}, material});
  s.triangles.push_back({{a, c, d}, material});
}

inline void finishScene(montecl::Scene& s) {
  if (s.materials.empty()) s.materials.push_back(montecl::MaterialDesc{});
  s.boundsMin = glm::vec3(1e30f);
  s.boundsMax = glm::vec3(-1e30f);
  for (const auto& t : s.triangles)
    for (const auto& v : t.v) {
      s.boundsMin = glm::min(s.boundsMin, v);
      s.boundsMax = glm::max(s.boundsMax, v);
    }
}

// The floor y = 0, 2000 units wide. Its two triangles' shared diagonal passes about 30 units
// from the origin: on triangles this large, a ray through the diagonal can slip between the two
// (the intersection test is not watertight at a 1e-4 scale), so test points stay away from it.
inline void addFloor(montecl::Scene& s, std::uint32_t material = 0) {
  const float r = 1000.0f, dx = 43.0f;
  addQuad(s, {-r + dx, 0, -r}, {-r + dx, 0, r}, {r + dx, 0, r}, {r + dx, 0, -r}, material);
}

// The floor, seen from above by a camera looking straight down at `at`.
inline montecl::Scene floorScene(glm::vec3 at, float height, float fovY, int size, int spp) {
  montecl::Scene s;
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

// The floor plus a wall x = 0 (y from 0 to 1000, z within +-1000), camera looking down at the
// floor around x = -0.5: AO there is 1/2 up to the wall's finite size (about 1e-3).
inline montecl::Scene wallScene(int size, int spp) {
  montecl::Scene s = floorScene({-0.5f, 0.0f, 0.0f}, 0.5f, 40.0f, size, spp);
  const float r = 1000.0f;
  addQuad(s, {0, 0, -r}, {0, r, -r}, {0, r, r}, {0, 0, r});
  finishScene(s);
  return s;
}

}  // namespace montecl_test
