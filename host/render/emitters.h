// emitters.h: what emits, and the light-selection table for direct lighting: every triangle whose
// material emits, in input order (Emitter::tri: its canonical slot in the BVH's triangles), with
// a CDF proportional to area * luminance(Ke). The one rule: a triangle emits when
// area * luminance(Ke) > 0 (emitterWeight); the kernels sample the table with pick_emitter and
// sample_triangle (kernels/shared/lights.h).
#pragma once
#include <vector>

#include "bvh/bvh.h"
#include "scene/scene.h"

namespace montecl {

struct EmitterTable {
  std::vector<Emitter> emitters;  // empty when nothing emits
  float totalPower = 0.0f;        // sum of area * luminance(Ke)
};

// Light-selection weight of a triangle of this area and emission: area * luminance(Ke); it emits
// when the weight is > 0.
double emitterWeight(float area, const glm::vec3& emission);

EmitterTable buildEmitterTable(const Bvh& bvh, const std::vector<MaterialDesc>& materials);

// Whether any triangle of the scene emits, by the table's rule (the direct integrator renders
// black without one).
bool hasEmitter(const Scene& scene);

}  // namespace montecl
