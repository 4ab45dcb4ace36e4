// bvh_traverse.cpp: host reference traversal. Runs the kernels' own closest-hit and any-hit code
// (kernels/shared/traverse_wide.h and traverse_binary.h, compiled as C++ through compat.h) over a
// Bvh built on the host, in the layout asked for.
// Hit::tri is the index into Bvh::triangles (BVH order); Bvh::order maps it back to the input.
#include "bvh/bvh.h"
#include "kernels/shared/traverse.h"

namespace montecl {

Hit intersectClosest(const Bvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                     BvhLayout layout, const AlphaScene* alpha) {
  if (bvh.nodes.empty()) {
    Hit miss;
    miss.t = INFINITY;
    miss.tri = MCL_NO_HIT;
    miss.u = miss.v = 0.0f;
    return miss;
  }
  if (layout == BvhLayout::Binary)
    return binary_closest_hit(bvh.nodes.data(), bvh.triangles.data(), alpha, org, dir, tmax);
  return wide_closest_hit(bvh.wideNodes().data(), bvh.triangles.data(), alpha, org, dir, tmax);
}

bool intersectAny(const Bvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                  BvhLayout layout, const AlphaScene* alpha) {
  if (bvh.nodes.empty()) return false;
  if (layout == BvhLayout::Binary)
    return binary_any_hit(bvh.nodes.data(), bvh.triangles.data(), alpha, org, dir, tmax) != 0;
  return wide_any_hit(bvh.wideNodes().data(), bvh.triangles.data(), alpha, org, dir, tmax) != 0;
}

}  // namespace montecl
