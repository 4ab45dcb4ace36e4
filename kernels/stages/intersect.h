// intersect: reads rays[0 .. *rayCount) and the BVH; writes the closest hit of each to hits.
// Launched for camera rays and, bound to the bounce buffers, for direct lighting's BRDF rays.
// Hits on cut-outs whose alpha is below their cutoff do not exist (surface_texture.h); scenes
// without textures skip the test. A ray with a NaN or infinite origin or direction is a miss and counted in *nanRays.
// With instances (frame->instanceCount > 0) the two-level BVH is traversed and each hit's instance
// written to hitInstances.
#pragma once
#include "stage_common.h"

MCL_INLINE void intersect_item(const intersect_args* a, uint i) {
  if (i >= *a->rayCount) return;
  Ray r = a->rays[i];
  if (!ray_is_finite(xyz(r.origin), xyz(r.dir))) MCL_ATOMIC_INC(a->nanRays);
  AlphaScene as;
  const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
  if (a->frame->instanceCount > 0u) {  // the two-level BVH: the hit and its instance
    InstanceHit ih = bvh_instances_closest_hit(a->nodes, a->tris, a->instances, alpha, xyz(r.origin), xyz(r.dir), r.dir.w);
    a->hits[i] = ih.hit;
    // World-space triangles (mesh 0, placed by the identity) shade as without instances.
    a->hitInstances[i] =
        ih.instance != MCL_NO_INSTANCE && a->instances[ih.instance].mesh != 0u ? ih.instance : MCL_NO_INSTANCE;
    return;
  }
  a->hits[i] = bvh_closest_hit(a->nodes, a->tris, alpha, xyz(r.origin), xyz(r.dir), r.dir.w);
}
