// bvh_internal.h: builder entry point with an explicit depth cap, for tests. buildBvh() is
// buildBvhCapped(tris, options, MCL_BVH_STACK_SIZE - 1).
#pragma once
#include "bvh/bvh.h"

namespace montecl {

// Like buildBvh, but no leaf lies deeper than maxDepth edges below the root (SAH splits that could
// break that become median splits). Throws std::invalid_argument when maxDepth is below
// ceil(log2(tris.size())), the depth a median split needs, or above MCL_BVH_STACK_SIZE - 1.
Bvh buildBvhCapped(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options,
                   int maxDepth);

}  // namespace montecl
