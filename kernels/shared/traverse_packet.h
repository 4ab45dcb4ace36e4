// traverse_packet.h: closest-hit traversal of the 8-wide BVH (WideNode) for a packet of W =
// MCL_LANES rays (lanes.h) with one shared stack: each visited node's eight child boxes are tested
// child by child against every active ray of the packet (W-lane slab tests, the operations of
// wide_entry per lane), the children that any ray enters are pushed with the mask of rays that
// entered them and the nearest entry distance among those rays (the packet's order key and its
// cull on pop), and leaf triangles are tested one by one for all rays of the popped entry
// (ray_triangle4's operations per lane). Pure; W > 1 only (OpenCL).
//
// Same hit as wide_closest_hit per ray: both return the nearest t over the triangles a ray
// intersects (the same box and triangle arithmetic per ray), and the scalar code keeps the first
// triangle found at that t, which depends on its visit order. A lane whose nearest t is also the t
// of a second triangle (another canonical slot or other barycentrics) is returned in the redo mask
// for the caller to run through wide_closest_hit. The packet's rays share one octant (the near and
// far bound rows of each axis), which the caller checks.
#pragma once
#include "lanes.h"
#include "traverse_wide.h"

#if MCL_LANES > 1
MCL_INLINE float v_hmin(vfloat x) {
#if MCL_LANES == 16
  float8 a8 = fmin(x.lo, x.hi);
  float4 b = fmin(a8.lo, a8.hi);
#elif MCL_LANES == 8
  float4 b = fmin(x.lo, x.hi);
#else
  float4 b = x;
#endif
  float2 c = fmin(b.lo, b.hi);
  return fmin(c.x, c.y);
}
// Bit k set where lane k of m is set, and back.
MCL_INLINE uint v_bits(vmask m) {
  vuint b = v_mask01(m) << v_lane_index();
#if MCL_LANES == 16
  uint8 b8 = b.lo | b.hi;
  uint4 b4 = b8.lo | b8.hi;
#elif MCL_LANES == 8
  uint4 b4 = b.lo | b.hi;
#else
  uint4 b4 = b;
#endif
  uint2 b2 = b4.lo | b4.hi;
  return b2.x | b2.y;
}
MCL_INLINE vmask v_from_bits(uint bits) { return ((v_u(bits) >> v_lane_index()) & 1u) != 0u; }
// Lane-wise mcl_max_nan1 / mcl_min_nan1 (a NaN in the first operand yields the second).
MCL_INLINE vfloat v_max_nan1(vfloat a, vfloat b) { return vsel(a > b, a, b); }
MCL_INLINE vfloat v_min_nan1(vfloat a, vfloat b) { return vsel(a < b, a, b); }

// The rays (origin o, inverse direction inv from safe_inverse, per lane) of the lanes set in act,
// all in the octant whose near rows are nearX, nearY, nearZ (WideNode::bounds rows, as in
// make_ray_box_ctx). *ht holds each ray's tmax on entry; on return t, slot (BVH order, not yet
// canonical: see the caller), u, v of the nearest hit of each active lane (tri MCL_NO_HIT and t
// unchanged on a miss). Returns the lanes to redo with the scalar traversal.
MCL_INLINE vmask packet_closest_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                    vfloat3 o, vfloat3 d, vfloat3 inv, vmask act, uint nearX, uint nearY,
                                    uint nearZ, vfloat* ht, vuint* htri, vuint* hcanon, vfloat* hu, vfloat* hv) {
  const uint farX = 1u - nearX, farY = 5u - nearY, farZ = 9u - nearZ;
  uint stackRef[MCL_WIDE_STACK_SIZE], stackBits[MCL_WIDE_STACK_SIZE];
  float stackKey[MCL_WIDE_STACK_SIZE];
  uint sp = 0;
  vmask redo = v_not(act) & v_not(act);  // none
  uint ref = 0u;
  vmask m = act;
  for (;;) {
    if (ref == MCL_WIDE_EMPTY) {
    } else if (ref & MCL_WIDE_LEAF) {
      uint firstTri = wide_leaf_first(ref), last = firstTri + wide_leaf_count(ref) - 1u;
      for (uint j = firstTri; j <= last; ++j) {
        float4 tv0 = tris[j].v0, te1 = tris[j].e1, te2 = tris[j].e2;
        vfloat px = d.y * te2.z - te2.y * d.z;  // cross(dir, e2)
        vfloat py = d.z * te2.x - te2.z * d.x;
        vfloat pz = d.x * te2.y - te2.x * d.y;
        vfloat det = te1.x * px + te1.y * py + te1.z * pz;
        vfloat idet = 1.0f / det;
        vfloat sx = o.x - tv0.x, sy = o.y - tv0.y, sz = o.z - tv0.z;
        vfloat u = (sx * px + sy * py + sz * pz) * idet;
        vfloat qx = sy * te1.z - te1.y * sz;  // cross(s, e1)
        vfloat qy = sz * te1.x - te1.z * sx;
        vfloat qz = sx * te1.y - te1.x * sy;
        vfloat v = (d.x * qx + d.y * qy + d.z * qz) * idet;
        vfloat t = (te2.x * qx + te2.y * qy + te2.z * qz) * idet;
        vmask bad = (fabs(det) < 1e-30f) | (u < 0.0f) | (u > 1.0f) | (v < 0.0f) | ((u + v) > 1.0f);
        vmask hitc = m & v_not(bad) & (t > 0.0f);
        vmask nearer = hitc & (t < *ht);
        vmask tie = hitc & (t == *ht) & (*htri != MCL_NO_HIT);
        if (!v_any(nearer | tie)) continue;
        uint canon = as_uint(te1.w);
        tie = tie & ((*hcanon != canon) | (u != *hu) | (v != *hv));
        redo = (redo & v_not(nearer)) | tie;
        *ht = vsel(nearer, t, *ht);
        *htri = vsel(nearer, v_u(j), *htri);
        *hcanon = vsel(nearer, v_u(canon), *hcanon);
        *hu = vsel(nearer, u, *hu);
        *hv = vsel(nearer, v, *hv);
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      uint base = sp, top = sp;
      for (uint c = 0; c < MCL_WIDE_WIDTH; ++c) {
        uint child = n->child[c];
        if (child == MCL_WIDE_EMPTY) continue;
        vfloat tnx = (n->bounds[nearX][c] - o.x) * inv.x;
        vfloat tfx = (n->bounds[farX][c] - o.x) * inv.x;
        vfloat tny = (n->bounds[nearY][c] - o.y) * inv.y;
        vfloat tfy = (n->bounds[farY][c] - o.y) * inv.y;
        vfloat tnz = (n->bounds[nearZ][c] - o.z) * inv.z;
        vfloat tfz = (n->bounds[farZ][c] - o.z) * inv.z;
        vfloat tmin = v_max_nan1(tnx, v_max_nan1(tny, v_max_nan1(tnz, v_f(0.0f))));
        vfloat tmx = v_min_nan1(tfx, v_min_nan1(tfy, v_min_nan1(tfz, *ht)));
        vmask in = m & (tmin <= tmx);
        if (!v_any(in)) continue;
        stackRef[top] = child;
        stackBits[top] = v_bits(in);
        stackKey[top] = v_hmin(vsel(in, tmin, v_f(INFINITY)));
        ++top;
      }
      // Farthest key deepest (insertion sort of the run; stable, the lower child nearer the top).
      for (uint p = base + 1u; p < top; ++p) {
        float dk = stackKey[p];
        uint rk = stackRef[p], bk = stackBits[p];
        uint b = p;
        for (; b > base && stackKey[b - 1u] <= dk; --b) {
          stackKey[b] = stackKey[b - 1u];
          stackRef[b] = stackRef[b - 1u];
          stackBits[b] = stackBits[b - 1u];
        }
        stackKey[b] = dk;
        stackRef[b] = rk;
        stackBits[b] = bk;
      }
      sp = top;
    }
    // Pop the next entry that some of its rays still enter at or before their nearest hit.
    int found = 0;
    while (sp > 0u) {
      --sp;
      m = v_from_bits(stackBits[sp]) & (stackKey[sp] <= *ht);
      if (v_any(m)) {
        ref = stackRef[sp];
        found = 1;
        break;
      }
    }
    if (!found) return redo;
  }
}
#endif
