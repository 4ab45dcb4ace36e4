// intersect_shadow_lanes.h: the packet form of intersect_shadow (intersect_shadow.h), the same
// contributions: W consecutive occlusion queries, one per lane, through one packet any-hit
// traversal (shared/traverse_packet_any.h) when they are coherent enough to share it: all finite
// and in one octant (one pixel's samples towards a light), or any rays in a small tree
// (FrameParams::packetAllRays); cut-outs' alpha test runs per lane inside it. Scenes with
// instances, a partial last packet and the binary BVH layout run the scalar body per query.
#pragma once
#include "intersect_shadow.h"
#include "stage_lanes.h"
#include "../shared/traverse_packet_any.h"

#if MCL_LANES > 1 && !defined(MCL_BVH_BINARY)
// Queries first .. first + n - 1 (all below *queueCount) through the single-ray any-hit, two at a
// time interleaved (wide_any_hit2) where no instances are placed; the same contributions as
// intersect_shadow_item per query.
MCL_INLINE void intersect_shadow_each(const intersect_shadow_args* a, uint first, uint n) {
  uint k = 0;
  if (a->frame->instanceCount == 0u) {
    AlphaScene as;
    const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
    for (; k + 1u < n; k += 2u) {
      ShadowWork w0 = a->queue[first + k], w1 = a->queue[first + k + 1u];
      int finite0 = ray_is_finite(xyz(w0.ray.origin), xyz(w0.ray.dir));
      int finite1 = ray_is_finite(xyz(w1.ray.origin), xyz(w1.ray.dir));
      if (!finite0) MCL_ATOMIC_INC(a->nanRays);
      if (!finite1) MCL_ATOMIC_INC(a->nanRays);
      int blocked0, blocked1;
      wide_any_hit2(a->nodes, a->tris, alpha, xyz(w0.ray.origin), xyz(w0.ray.dir), w0.ray.dir.w,
                    xyz(w1.ray.origin), xyz(w1.ray.dir), w1.ray.dir.w, &blocked0, &blocked1);
      // A non-finite query is blocked (intersect_shadow_item), though no traversal finds a hit.
      if (finite0 && !blocked0) a->shadowContrib[w0.slot] = make_float4(w0.r, w0.g, w0.b, 0.0f);
      if (finite1 && !blocked1) a->shadowContrib[w1.slot] = make_float4(w1.r, w1.g, w1.b, 0.0f);
    }
  }
  for (; k < n; ++k) intersect_shadow_item(a, first + k);
}
#endif

MCL_INLINE void stage_intersect_shadow(const intersect_shadow_args* a, uint first) {
#if MCL_LANES == 1 || defined(MCL_BVH_BINARY)
  for (uint k = 0; k < MCL_LANES; ++k) intersect_shadow_item(a, first + k);
#else
  uint count = *a->queueCount;
  if (first >= count) return;
  if (packet_traversal_unfit(a->frame, first, count)) {
    intersect_shadow_each(a, first, min(count - first, (uint)MCL_LANES));
    return;
  }
  // ShadowWork: the ray's origin and direction (w: tmax), then r, g, b, slot; 12 floats each.
  vfloat ox, oy, oz, ow, dx, dy, dz, tmax;
  v_load4_stride((MCL_GLOBAL const float*)(a->queue + first), 12, &ox, &oy, &oz, &ow);
  v_load4_stride((MCL_GLOBAL const float*)(a->queue + first) + 4, 12, &dx, &dy, &dz, &tmax);
  vfloat3 o = v3_make(ox, oy, oz), d = v3_make(dx, dy, dz), inv;
  vmask finite, nx, ny, nz;
  int octant = packet_ray_setup(o, d, &inv, &finite, &nx, &ny, &nz);
  if (!v_all(finite) || !(octant || a->frame->packetAllRays)) {
    intersect_shadow_each(a, first, MCL_LANES);
    return;
  }
  AlphaScene as;
  const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
  vmask blocked = packet_any_hit(a->nodes, a->tris, alpha, o, d, inv, finite, nx, ny, nz, tmax, packet_switch(a->frame));
  uint bits = v_bits(v_not(blocked));
  while (bits != 0u) {
    uint k = mcl_ctz(bits);
    bits &= bits - 1u;
    MCL_GLOBAL const ShadowWork* w = a->queue + first + k;
    a->shadowContrib[w->slot] = make_float4(w->r, w->g, w->b, 0.0f);
  }
#endif
}
