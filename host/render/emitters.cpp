// emitters.cpp: builds the emitter CDF on the host (in double, stored as float; the last entry
// is exactly 1 so every u in [0, 1) picks an emitter), over the input triangles in input order.
#include "render/emitters.h"

#include "kernels/shared/lights.h"

namespace montecl {

double emitterWeight(float area, const glm::vec3& emission) {
  return double(area) * double(luminance(emission));
}

EmitterTable buildEmitterTable(const Bvh& bvh, const std::vector<MaterialDesc>& materials) {
  EmitterTable table;
  std::vector<double> power;
  double total = 0.0;
  // Input order, each triangle through its canonical slot (a spatial split's copies are skipped):
  // the table, and so the light samples, do not depend on the tree.
  const std::size_t m = bvh.triangles.size();
  std::vector<std::uint32_t> slots;
  if (bvh.order.size() == m) {
    slots.assign(m, MCL_NO_HIT);
    for (std::size_t i = 0; i < m; ++i)
      if (as_uint(bvh.triangles[i].e1.w) == i && bvh.order[i] < m) slots[bvh.order[i]] = std::uint32_t(i);
  } else {  // a Bvh assembled by hand (no order): its slots as they are
    for (std::size_t i = 0; i < m; ++i) slots.push_back(std::uint32_t(i));
  }
  for (std::uint32_t i : slots) {
    if (i == MCL_NO_HIT) continue;
    const Triangle& t = bvh.triangles[i];
    const glm::vec3 le = materials[triangle_material(&t)].emission;
    float area = triangle_area(&t);
    double p = emitterWeight(area, le);
    if (!(p > 0.0)) continue;
    Emitter e{};
    e.tri = uint(i);
    e.area = area;
    table.emitters.push_back(e);
    power.push_back(p);
    total += p;
  }
  double running = 0.0;
  for (std::size_t k = 0; k < table.emitters.size(); ++k) {
    running += power[k];
    table.emitters[k].cdf = float(running / total);
  }
  if (!table.emitters.empty()) table.emitters.back().cdf = 1.0f;
  table.totalPower = float(total);
  return table;
}

bool hasEmitter(const Scene& scene) {
  for (const SceneTriangle& t : scene.triangles) {
    const glm::vec3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];  // as Bvh::triangles holds them
    if (emitterWeight(0.5f * glm::length(glm::cross(e1, e2)), scene.materials[t.material].emission) > 0.0)
      return true;
  }
  return false;
}

}  // namespace montecl
