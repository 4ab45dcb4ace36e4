// intersect_shadow: reads queue[0 .. *queueCount) of occlusion queries and the BVH; writes the
// contribution of each unblocked query to its shadow slot (any hit, up to the query's tmax; cut-outs
// block only where their alpha passes the cutoff, surface_texture.h). A
// query with a NaN or infinite origin or direction is blocked (its contribution stays 0) and
// counted in *nanRays.
#pragma once
#include "stage_common.h"

MCL_INLINE void intersect_shadow_item(const intersect_shadow_args* a, uint k) {
  if (k >= *a->queueCount) return;
  ShadowWork w = a->queue[k];
  if (!ray_is_finite(xyz(w.ray.origin), xyz(w.ray.dir))) {
    MCL_ATOMIC_INC(a->nanRays);
    return;
  }
  AlphaScene as;
  const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
  const int blocked = a->frame->instanceCount > 0u  // the two-level BVH
                          ? bvh_instances_any_hit(a->nodes, a->tris, a->instances, alpha, xyz(w.ray.origin),
                                                  xyz(w.ray.dir), w.ray.dir.w)
                          : bvh_any_hit(a->nodes, a->tris, alpha, xyz(w.ray.origin), xyz(w.ray.dir), w.ray.dir.w);
  if (!blocked) a->shadowContrib[w.slot] = make_float4(w.r, w.g, w.b, 0.0f);
}
