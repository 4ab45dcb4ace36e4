// path_gather: after intersect_shadow, for each path shaded this bounce (the queue pathIds[0 ..
// *rayCount); identity at bounce 0), adds its shadow slots (the unblocked next-event estimates, in
// slot order) to radiance[id] and clears them, so the sum does not depend on the queue's order and
// accumulate later adds zeros. Entries first .. first + W - 1, one per lane (the paths of a
// packet are distinct, so the lanes' gathers and scatters never meet).
#pragma once
#include "stage_lanes.h"

MCL_INLINE void stage_path_gather(const path_gather_args* a, uint first) {
  const uint count = *a->rayCount;
  if (first >= count) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, count), slots = f->shadowSlots;
  vuint k = first + vsel(v_lane_index() < lanes, v_lane_index(), v_u(lanes - 1u));  // lanes past the packet: its last entry
  vuint id = a->pathBounce == 0 ? k : v_gather_uint(a->pathIds, k);
  MCL_GLOBAL float* rad = (MCL_GLOBAL float*)a->radiance;
  MCL_GLOBAL float* sc = (MCL_GLOBAL float*)a->shadowContrib;
  vfloat x, y, z, w, sx, sy, sz, sw;
  v_gather4(rad, id, 4u, &x, &y, &z, &w);
  for (uint s = 0; s < slots; ++s) {
    vuint slot = id * slots + s;
    v_gather4(sc, slot, 4u, &sx, &sy, &sz, &sw);
    x = x + sx;
    y = y + sy;
    z = z + sz;
    v_scatter4_n(sc, slot, 4u, lanes, v_f(0.0f), v_f(0.0f), v_f(0.0f), v_f(0.0f));
  }
  v_scatter4_n(rad, id, 4u, lanes, x, y, z, v_f(0.0f));
}
