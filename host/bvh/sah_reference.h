// sah_reference.h: the SAH cost of a full-sweep build (every object split along every axis, from
// sorted centroids), the slow best-quality reference the binned builder is measured against
// (`montecl bench --sah-reference`, tests/test_bvh.cpp). Reads triangles; builds no tree.
#pragma once
#include <vector>

#include "bvh/bvh.h"

namespace montecl {

// SAH cost, relative to the root box's area, of the binary tree a full-sweep SAH build with the
// same leaf rule and costs as buildBvh(tris, options) would make. O(n log^2 n): seconds for 1M.
double fullSweepSahCost(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options);

}  // namespace montecl
