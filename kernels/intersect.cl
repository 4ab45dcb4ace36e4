// intersect: reads rays[0 .. *rayCount) and the BVH; writes the closest hit of each to hits.
#include "shared/stages.h"

__kernel void intersect(__global const BvhTraversalNode* nodes, __global const Triangle* tris,
                        __global const Ray* rays, __global const uint* rayCount,
                        __global Hit* hits) {
  uint i = get_global_id(0);
  if (i < *rayCount) stage_intersect(nodes, tris, rays, i, hits);
}
