// intersect: reads rays[0 .. *rayCount) and the BVH; writes the closest hit of each to hits.
// Launched for camera rays and, bound to the bounce buffers, for direct lighting's BRDF rays.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_intersect(const intersect_args* a, uint i) {
  if (i >= *a->rayCount) return;
  Ray r = a->rays[i];
  a->hits[i] = bvh_closest_hit(a->nodes, a->tris, xyz(r.origin), xyz(r.dir), r.dir.w);
}
