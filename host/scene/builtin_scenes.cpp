// builtin_scenes.cpp: the analytic scenes of builtin_scenes.h.
#include "scene/builtin_scenes.h"

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
