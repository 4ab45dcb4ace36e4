// intersect_shadow_lanes.h: the packet form of intersect_shadow (intersect_shadow.h), the same
// contributions: W consecutive occlusion queries, one per lane, through one packet any-hit
// traversal (shared/traverse_packet_any.h) when they are coherent enough to share it: all finite
// and in one octant (one pixel's samples towards a light), or any rays in a small tree
// (FrameParams::packetAllRays). Scenes with textures (alpha-tested cut-outs) or instances, a
// partial last packet and the binary BVH layout run the scalar body per query.
#pragma once
#include "intersect_shadow.h"
#include "stage_lanes.h"
#include "../shared/traverse_packet_any.h"

MCL_INLINE void stage_intersect_shadow_lanes(const intersect_shadow_args* a, uint first) {
#if MCL_LANES == 1 || defined(MCL_BVH_BINARY)
  for (uint k = 0; k < MCL_LANES; ++k) stage_intersect_shadow(a, first + k);
#else
  uint count = *a->queueCount;
  if (first >= count) return;
  if (packet_traversal_unfit(a->frame, first, count)) {
    for (uint k = 0; k < MCL_LANES && first + k < count; ++k) stage_intersect_shadow(a, first + k);
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
    for (uint k = 0; k < MCL_LANES; ++k) stage_intersect_shadow(a, first + k);
    return;
  }
  vmask blocked = packet_any_hit(a->nodes, a->tris, o, d, inv, finite, nx, ny, nz, tmax, packet_switch(a->frame));
  uint bits = v_bits(v_not(blocked));
  while (bits != 0u) {
    uint k = mcl_ctz(bits);
    bits &= bits - 1u;
    MCL_GLOBAL const ShadowWork* w = a->queue + first + k;
    a->shadowContrib[w->slot] = make_float4(w->r, w->g, w->b, 0.0f);
  }
#endif
}
