// sah_reference.h: SAH costs of two reference builds the binned builder is measured against
// (`montecl bench --sah-reference`, tests/test_bvh.cpp): a full sweep (every object split along
// every axis, from sorted centroids; slow, best greedy quality) and an object-median build (fast,
// poor). Reads triangles; builds no tree.
#pragma once
#include <vector>

#include "bvh/bvh.h"

namespace montecl {

// SAH cost, relative to the root box's area, of the binary tree a full-sweep SAH build with the
// same leaf rule and costs as buildBvh(tris, options) would make. O(n log^2 n): seconds for 1M.
double fullSweepSahCost(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options);

// SAH cost of a build that splits every node of more than maxLeafSize triangles at the object
// median along its widest centroid axis.
double medianSplitSahCost(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options);

}  // namespace montecl
