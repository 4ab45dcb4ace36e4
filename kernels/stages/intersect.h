// intersect: reads rays[0 .. *rayCount) and the BVH; writes the closest hit of each to hits.
// Launched for camera rays and, bound to the bounce buffers, for direct lighting's BRDF rays.
// A ray with a NaN or infinite origin or direction is a miss and counted in *nanRays.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_intersect(const intersect_args* a, uint i) {
  if (i >= *a->rayCount) return;
  Ray r = a->rays[i];
  if (!ray_is_finite(xyz(r.origin), xyz(r.dir))) MCL_ATOMIC_INC(a->nanRays);
  a->hits[i] = bvh_closest_hit(a->nodes, a->tris, xyz(r.origin), xyz(r.dir), r.dir.w);
}
