// traverse_packet_any.h: any-hit (occlusion) traversal of the 8-wide BVH for a packet of W =
// MCL_LANES rays with one shared stack: each visited node's child boxes are tested against every
// ray of the packet not yet blocked (v_child_entry), the entered children pushed with the mask of
// rays that entered them, and leaf triangles tested for all those rays at once (v_ray_triangle; a
// cut-out blocks only the rays its alpha test passes for, v_alpha_hits);
// a ray leaves the packet at its first hit, and the traversal ends when every ray is blocked or
// the stack is empty. An entry that few unblocked rays still enter is traversed ray by ray
// (wide_any_hit_from). Pure; W > 1 only (OpenCL).
//
// Same answer as wide_any_hit per ray: a ray is blocked exactly when some triangle whose every
// ancestor box the ray enters (the same slab arithmetic, against the same constant tmax) passes the
// same triangle test with t in (0, tmax). That set does not depend on the visit order, and both
// traversals search it until a hit.
#pragma once
#include "traverse_packet.h"

#if MCL_LANES > 1
// The rays (origin o, direction d, inverse inv from packet_ray_setup with its nx, ny, nz) of the
// lanes set in act, each with its own tmax: returns the lanes blocked by some triangle (alpha,
// which may be null, as in the single-ray any-hit). An entry
// at most switchAt unblocked rays enter goes on ray by ray (packet_switch).
MCL_INLINE vmask packet_any_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                const AlphaScene* alpha, vfloat3 o,
                                vfloat3 d, vfloat3 inv, vmask act, vmask nx, vmask ny, vmask nz, vfloat tmax,
                                uint switchAt) {
  uint stackRef[MCL_WIDE_STACK_SIZE], stackBits[MCL_WIDE_STACK_SIZE];
  uint sp = 0;
  vmask blocked = v_not(act) & act;  // none
  uint ref = 0u;
  vmask m = act;
  // The rays lane by lane, for the entries few of them enter (stored once per packet).
  float ox[MCL_LANES] MCL_LANE_ALIGN, oy[MCL_LANES] MCL_LANE_ALIGN, oz[MCL_LANES] MCL_LANE_ALIGN;
  float dx[MCL_LANES] MCL_LANE_ALIGN, dy[MCL_LANES] MCL_LANE_ALIGN, dz[MCL_LANES] MCL_LANE_ALIGN;
  float tm[MCL_LANES] MCL_LANE_ALIGN;
  v3_store_lanes(o, ox, oy, oz);
  v3_store_lanes(d, dx, dy, dz);
  v_store_lanes(tmax, tm);
  for (;;) {
    if (ref == MCL_WIDE_EMPTY) {
    } else if (ref & MCL_WIDE_LEAF) {
      uint firstTri = wide_leaf_first(ref), last = firstTri + wide_leaf_count(ref) - 1u;
      for (uint j = firstTri; j <= last; ++j) {
        vfloat u, v;
        vmask bad;
        vfloat t = v_ray_triangle(tris, j, o, d, &u, &v, &bad);
        vmask hit = m & v_not(bad) & (t > 0.0f) & (t < tmax);
        if (!v_any(hit)) continue;
        hit = v_alpha_hits(alpha, tris, j, hit, u, v, o, d);
        blocked = blocked | hit;
        m = m & v_not(hit);
        if (!v_any(m)) break;
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      for (uint c = 0; c < MCL_WIDE_WIDTH; ++c) {
        uint child = n->child[c];
        if (child == MCL_WIDE_EMPTY) continue;
        vfloat tmin;
        vmask in = v_child_entry(n, c, o, inv, nx, ny, nz, m, tmax, &tmin);
        if (!v_any(in)) continue;
        stackRef[sp] = child;
        stackBits[sp] = v_bits(in);
        ++sp;
      }
    }
    // Pop the next entry some unblocked ray still enters; few such rays go on one by one.
    uint open = v_bits(v_not(blocked) & act);
    int found = 0;
    while (sp > 0u && open != 0u) {
      --sp;
      uint bits = stackBits[sp] & open;
      if (bits == 0u) continue;
      if (popcount(bits) > switchAt) {
        ref = stackRef[sp];
        m = v_from_bits(bits);
        found = 1;
        break;
      }
      while (bits != 0u) {
        uint k = mcl_ctz(bits);
        bits &= bits - 1u;
        if (wide_any_hit_from(nodes, tris, alpha, make_float3(ox[k], oy[k], oz[k]), make_float3(dx[k], dy[k], dz[k]),
                              tm[k], stackRef[sp]))
          open &= ~(1u << k);
      }
    }
    blocked = act & v_not(v_from_bits(open));  // with the rays blocked one by one
    if (!found) return blocked;
  }
}
#endif
