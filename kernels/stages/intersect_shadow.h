// intersect_shadow: reads the occlusion queries first .. first + W - 1 below *queueCount, one per
// lane (W = MCL_LANES: 1 on the host backend and GPUs), and the BVH; writes the contribution of
// each unblocked query to its shadow slot (any hit, up to the query's tmax; cut-outs block only
// where their alpha passes the cutoff, stochastically transparent surfaces only where their coin
// says the hit exists: the test camera and bounce rays take, surface_texture.h). A packet coherent enough to share one
// traversal (all finite and in one octant: one pixel's samples towards a light; or any rays in a
// small tree, FrameParams::packetAllRays) takes the packet any-hit traversal
// (shared/traverse_packet_any.h, the alpha test per lane); the others (a partial last packet,
// scenes with instances, the binary BVH layout, W = 1) go query by query through the single-ray
// any-hit, two interleaved where it can. A query with a NaN or infinite origin or direction is
// blocked (its contribution stays 0) and counted in *nanRays.
#pragma once
#include "stage_lanes.h"
#include "../shared/traverse_packet_any.h"

// Query k through the single-ray any-hit.
MCL_INLINE void shadow_query(const intersect_shadow_args* a, const AlphaScene* alpha, uint k) {
  ShadowWork w = a->queue[k];
  if (!ray_is_finite(xyz(w.ray.origin), xyz(w.ray.dir))) {
    MCL_ATOMIC_INC(a->nanRays);
    return;
  }
  const int blocked = a->frame->instanceCount > 0u  // the two-level BVH
                          ? bvh_instances_any_hit(a->nodes, a->tris, a->instances, alpha, xyz(w.ray.origin),
                                                  xyz(w.ray.dir), w.ray.dir.w)
                          : bvh_any_hit(a->nodes, a->tris, alpha, xyz(w.ray.origin), xyz(w.ray.dir), w.ray.dir.w);
  if (!blocked) a->shadowContrib[w.slot] = make_float4(w.r, w.g, w.b, 0.0f);
}

// Queries first .. first + n - 1 one by one, two at a time interleaved (wide_any_hit2) where no
// instances are placed and the layout is the wide one: the same contributions as shadow_query.
MCL_INLINE void shadow_each(const intersect_shadow_args* a, const AlphaScene* alpha, uint first, uint n) {
  uint k = 0;
#if MCL_LANES > 1 && !defined(MCL_BVH_BINARY)
  for (; a->frame->instanceCount == 0u && k + 1u < n; k += 2u) {
    ShadowWork w0 = a->queue[first + k], w1 = a->queue[first + k + 1u];
    int finite0 = ray_is_finite(xyz(w0.ray.origin), xyz(w0.ray.dir));
    int finite1 = ray_is_finite(xyz(w1.ray.origin), xyz(w1.ray.dir));
    if (!finite0) MCL_ATOMIC_INC(a->nanRays);
    if (!finite1) MCL_ATOMIC_INC(a->nanRays);
    int blocked0, blocked1;
    wide_any_hit2(a->nodes, a->tris, alpha, xyz(w0.ray.origin), xyz(w0.ray.dir), w0.ray.dir.w, xyz(w1.ray.origin),
                  xyz(w1.ray.dir), w1.ray.dir.w, &blocked0, &blocked1);
    // A non-finite query is blocked (shadow_query), though no traversal finds a hit.
    if (finite0 && !blocked0) a->shadowContrib[w0.slot] = make_float4(w0.r, w0.g, w0.b, 0.0f);
    if (finite1 && !blocked1) a->shadowContrib[w1.slot] = make_float4(w1.r, w1.g, w1.b, 0.0f);
  }
#endif
  for (; k < n; ++k) shadow_query(a, alpha, first + k);
}

MCL_INLINE void stage_intersect_shadow(const intersect_shadow_args* a, uint first) {
  const uint count = *a->queueCount;
  if (first >= count) return;
  AlphaScene as;
  const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
#if MCL_LANES > 1 && !defined(MCL_BVH_BINARY)
  if (!packet_traversal_unfit(a->frame, first, count)) {
    // ShadowWork: the ray's origin and direction (w: tmax), then r, g, b, slot; 12 floats each.
    vfloat ox, oy, oz, ow, dx, dy, dz, tmax;
    v_load4_stride((MCL_GLOBAL const float*)(a->queue + first), 12, &ox, &oy, &oz, &ow);
    v_load4_stride((MCL_GLOBAL const float*)(a->queue + first) + 4, 12, &dx, &dy, &dz, &tmax);
    vfloat3 o = v3_make(ox, oy, oz), d = v3_make(dx, dy, dz), inv;
    vmask finite, nx, ny, nz;
    int octant = packet_ray_setup(o, d, &inv, &finite, &nx, &ny, &nz);
    if (v_all(finite) && (octant || a->frame->packetAllRays)) {
      vmask blocked =
          packet_any_hit(a->nodes, a->tris, alpha, o, d, inv, finite, nx, ny, nz, tmax, packet_switch(a->frame));
      uint bits = v_bits(v_not(blocked));
      while (bits != 0u) {
        uint k = mcl_ctz(bits);
        bits &= bits - 1u;
        MCL_GLOBAL const ShadowWork* w = a->queue + first + k;
        a->shadowContrib[w->slot] = make_float4(w->r, w->g, w->b, 0.0f);
      }
      return;
    }
  }
#endif
  shadow_each(a, alpha, first, v_packet_lanes(first, count));
}
