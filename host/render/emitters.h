// emitters.h: the light-selection table for direct lighting: every BVH-ordered triangle whose
// material emits, with a CDF proportional to area * luminance(Ke).
#pragma once
#include <vector>

#include "bvh/bvh.h"

namespace montecl {

struct EmitterTable {
  std::vector<Emitter> emitters;  // empty when nothing emits
  float totalPower = 0.0f;        // sum of area * luminance(Ke)
};

EmitterTable buildEmitterTable(const Bvh& bvh, const std::vector<MaterialDesc>& materials);

}  // namespace montecl
