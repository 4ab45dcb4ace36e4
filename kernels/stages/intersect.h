// intersect: reads the rays first .. first + W - 1 below *rayCount, one per lane (W = MCL_LANES: 1
// on the host backend and GPUs), and the BVH; writes the closest hit of each to hits. Launched for
// camera rays and, bound to the bounce buffers, for direct lighting's BRDF rays. A packet coherent
// enough to share one traversal (all finite and in one octant: camera rays; or any rays in a small
// tree, FrameParams::packetAllRays) takes the packet traversal (shared/traverse_packet.h); the
// others (incoherent bounce rays, a partial last packet, scenes with instances, the binary BVH
// layout, W = 1) go ray by ray through the single-ray traversal, two rays interleaved where it
// can. Hits on cut-outs whose alpha is below their cutoff, and on stochastically transparent
// surfaces whose coin says so, do not exist (surface_texture.h alpha_hit_exists; per lane inside
// the packet traversal); scenes without alpha-tested triangles skip the test. A ray with a NaN or
// infinite origin or direction is a miss and counted in *nanRays. With instances
// (frame->instanceCount > 0) the two-level BVH is traversed and each hit's instance written to
// hitInstances.
#pragma once
#include "stage_lanes.h"
#include "../shared/traverse_packet.h"

// Ray i through the single-ray traversal.
MCL_INLINE void intersect_ray(const intersect_args* a, const AlphaScene* alpha, uint i) {
  Ray r = a->rays[i];
  if (!ray_is_finite(xyz(r.origin), xyz(r.dir))) MCL_ATOMIC_INC(a->nanRays);
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

// Rays first .. first + n - 1 one by one, two at a time interleaved (wide_closest_hit2) where no
// instances are placed and the layout is the wide one: the same hits as intersect_ray per ray.
// MCL_INTERSECT_SCALAR: every ray through the single-ray traversal alone (for measurements).
MCL_INLINE void intersect_each(const intersect_args* a, const AlphaScene* alpha, uint first, uint n) {
  uint k = 0;
#if MCL_LANES > 1 && !defined(MCL_BVH_BINARY) && !defined(MCL_INTERSECT_SCALAR)
  for (; a->frame->instanceCount == 0u && k + 1u < n; k += 2u) {
    Ray r0 = a->rays[first + k], r1 = a->rays[first + k + 1u];
    if (!ray_is_finite(xyz(r0.origin), xyz(r0.dir))) MCL_ATOMIC_INC(a->nanRays);
    if (!ray_is_finite(xyz(r1.origin), xyz(r1.dir))) MCL_ATOMIC_INC(a->nanRays);
    Hit h0, h1;
    wide_closest_hit2(a->nodes, a->tris, alpha, xyz(r0.origin), xyz(r0.dir), r0.dir.w, xyz(r1.origin), xyz(r1.dir),
                      r1.dir.w, &h0, &h1);
    a->hits[first + k] = h0;
    a->hits[first + k + 1u] = h1;
  }
#endif
  for (; k < n; ++k) intersect_ray(a, alpha, first + k);
}

MCL_INLINE void stage_intersect(const intersect_args* a, uint first) {
  const uint count = *a->rayCount;
  if (first >= count) return;
  AlphaScene as;
  const AlphaScene* alpha = MCL_STAGE_ALPHA(a, as);
#if MCL_LANES > 1 && !defined(MCL_BVH_BINARY) && !defined(MCL_INTERSECT_SCALAR)
  if (!packet_traversal_unfit(a->frame, first, count)) {
    vfloat ox, oy, oz, ow, dx, dy, dz, tmax;
    v_load4_stride((MCL_GLOBAL const float*)(a->rays + first), 8, &ox, &oy, &oz, &ow);
    v_load4_stride((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, &dx, &dy, &dz, &tmax);
    vfloat3 inv;
    vmask finite, nx, ny, nz;
    int octant = packet_ray_setup(v3_make(ox, oy, oz), v3_make(dx, dy, dz), &inv, &finite, &nx, &ny, &nz);
    if (v_all(finite) && (octant || a->frame->packetAllRays)) {
      vfloat ht = tmax, hu = v_f(0.0f), hv = v_f(0.0f);
      vuint hcanon = v_u(MCL_NO_HIT);
      packet_closest_hit(a->nodes, a->tris, alpha, v3_make(ox, oy, oz), v3_make(dx, dy, dz), inv, finite, nx, ny, nz,
                         packet_switch(a->frame), &ht, &hcanon, &hu, &hv);
      ht = vsel(hcanon == MCL_NO_HIT, v_f(INFINITY), ht);
      v_store4((MCL_GLOBAL float*)(a->hits + first), ht, v_as_float(hcanon), hu, hv);
      return;
    }
  }
#endif
  intersect_each(a, alpha, first, v_packet_lanes(first, count));
}
