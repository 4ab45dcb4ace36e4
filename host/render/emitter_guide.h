// emitter_guide.h: the guide table of the emitter pick (Emitter::guide, kernels/shared/lights.h
// pick_emitter): fills it from the emitters' cdf.
#pragma once
#include <vector>

#include "kernels/shared/types.h"

namespace montecl {

// Sets emitters[k].guide to the index pick_emitter's whole-table search returns for the smallest
// float u in bucket k (emitter_guide_bucket), for every k. The cdf must be non-decreasing.
void fillEmitterGuide(std::vector<Emitter>& emitters);

}  // namespace montecl
