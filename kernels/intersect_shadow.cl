// intersect_shadow: reads queue[0 .. *queueCount) of occlusion queries and the BVH; writes the
// contribution of each unblocked query to its shadow slot (any-hit, up to the query's tmax).
#include "shared/stages.h"

__kernel void intersect_shadow(__global const BvhTraversalNode* nodes, __global const Triangle* tris,
                               __global const ShadowWork* queue, __global const uint* queueCount,
                               __global float4* shadowContrib) {
  uint k = get_global_id(0);
  if (k < *queueCount) stage_intersect_shadow(nodes, tris, queue, k, shadowContrib);
}
