// intersect_lanes.h: the packet form of intersect (intersect.h), the same hit per ray: W
// consecutive rays, one per lane, through one packet traversal (shared/traverse_packet.h) when
// they are coherent enough to share it: all finite and in one octant (camera rays; the incoherent
// bounce rays of direct lighting mostly fail this and take the scalar traversal per ray); cut-outs'
// alpha test runs per lane inside it. Scenes with instances, a partial last packet and the binary
// BVH layout run the scalar body.
#pragma once
#include "intersect.h"
#include "stage_lanes.h"
#include "../shared/traverse_packet.h"

#if MCL_LANES > 1 && !defined(MCL_BVH_BINARY)
// Items first .. first + n - 1 (all below *rayCount) through the single-ray traversal, two rays at
// a time interleaved (wide_closest_hit2) where no instances are placed; the same hits as
// intersect_item per item.
MCL_INLINE void intersect_each(const intersect_args* a, uint first, uint n) {
  uint k = 0;
  if (a->frame->instanceCount == 0u) {
    AlphaScene as;
    const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
    for (; k + 1u < n; k += 2u) {
      Ray r0 = a->rays[first + k], r1 = a->rays[first + k + 1u];
      if (!ray_is_finite(xyz(r0.origin), xyz(r0.dir))) MCL_ATOMIC_INC(a->nanRays);
      if (!ray_is_finite(xyz(r1.origin), xyz(r1.dir))) MCL_ATOMIC_INC(a->nanRays);
      Hit h0, h1;
      wide_closest_hit2(a->nodes, a->tris, alpha, xyz(r0.origin), xyz(r0.dir), r0.dir.w, xyz(r1.origin),
                        xyz(r1.dir), r1.dir.w, &h0, &h1);
      a->hits[first + k] = h0;
      a->hits[first + k + 1u] = h1;
    }
  }
  for (; k < n; ++k) intersect_item(a, first + k);
}
#endif

MCL_INLINE void stage_intersect(const intersect_args* a, uint first) {
#if MCL_LANES == 1 || defined(MCL_BVH_BINARY) || defined(MCL_INTERSECT_SCALAR)
  // MCL_INTERSECT_SCALAR: every item through the scalar traversal (for measurements).
  for (uint k = 0; k < MCL_LANES; ++k) intersect_item(a, first + k);
#else
  uint count = *a->rayCount;
  if (first >= count) return;
  if (packet_traversal_unfit(a->frame, first, count)) {
    intersect_each(a, first, min(count - first, (uint)MCL_LANES));
    return;
  }
  vfloat ox, oy, oz, ow, dx, dy, dz, tmax;
  v_load4_stride((MCL_GLOBAL const float*)(a->rays + first), 8, &ox, &oy, &oz, &ow);
  v_load4_stride((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, &dx, &dy, &dz, &tmax);
  vfloat3 inv;
  vmask finite, nx, ny, nz;
  int octant = packet_ray_setup(v3_make(ox, oy, oz), v3_make(dx, dy, dz), &inv, &finite, &nx, &ny, &nz);
  if (!v_all(finite) || !(octant || a->frame->packetAllRays)) {
    intersect_each(a, first, MCL_LANES);
    return;
  }
  vfloat ht = tmax, hu = v_f(0.0f), hv = v_f(0.0f);
  vuint hcanon = v_u(MCL_NO_HIT);
  AlphaScene as;
  const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
  packet_closest_hit(a->nodes, a->tris, alpha, v3_make(ox, oy, oz), v3_make(dx, dy, dz), inv, finite, nx, ny, nz,
                     packet_switch(a->frame), &ht, &hcanon, &hu, &hv);
  ht = vsel(hcanon == MCL_NO_HIT, v_f(INFINITY), ht);
  v_store4((MCL_GLOBAL float*)(a->hits + first), ht, v_as_float(hcanon), hu, hv);
#endif
}
