// traverse_packet.h: closest-hit traversal of the 8-wide BVH (WideNode) for a packet of W =
// MCL_LANES rays (lanes.h) with one shared stack: each visited node's eight child boxes are tested
// child by child against every active ray of the packet (W-lane slab tests, the operations of
// wide_entry per lane), the children that any ray enters are pushed with the mask of rays that
// entered them and the nearest entry distance among those rays (the packet's order key and its
// cull on pop), and leaf triangles are tested one by one for all rays of the popped entry
// (ray_triangle4's operations per lane); a cut-out's hits are kept only where its alpha test
// passes (v_alpha_hits). Pure; W > 1 only (OpenCL).
//
// Same hit as wide_closest_hit per ray: both keep the first hit in hit_before's order (nearest t,
// then the lowest canonical slot) over the triangles a ray intersects, with the same box and
// triangle arithmetic per ray, so the order in which the packet meets them does not matter. Each
// lane picks its own near and far box rows, so the rays need not share an octant (the callers
// decide when a packet pays: packet_ray_setup).
#pragma once
#include "lanes.h"
#include "traverse_wide.h"

#if MCL_LANES > 1
// The smallest lane of x, which holds no NaN (fmin's NaN handling costs a fix-up per step on x86).
MCL_INLINE float v_hmin(vfloat x) {
#if MCL_LANES == 16
  float8 a8 = x.lo < x.hi ? x.lo : x.hi;
  float4 b = a8.lo < a8.hi ? a8.lo : a8.hi;
#elif MCL_LANES == 8
  float4 b = x.lo < x.hi ? x.lo : x.hi;
#else
  float4 b = x;
#endif
  float2 c = b.lo < b.hi ? b.lo : b.hi;
  return c.x < c.y ? c.x : c.y;
}
// Bit k set where lane k of m is set, and back.
MCL_INLINE uint v_bits(vmask m) {
  vuint b = v_mask01(m) << v_lane_index();
#ifdef MCL_HAS_REDUCE
  return __builtin_reduce_or(b);
#else
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
#endif
}
MCL_INLINE vmask v_from_bits(uint bits) { return ((v_u(bits) >> v_lane_index()) & 1u) != 0u; }
// Lane-wise mcl_max_nan1 / mcl_min_nan1 (a NaN in the first operand yields the second).
MCL_INLINE vfloat v_max_nan1(vfloat a, vfloat b) { return vsel(a > b, a, b); }
MCL_INLINE vfloat v_min_nan1(vfloat a, vfloat b) { return vsel(a < b, a, b); }

// A packet's per-ray set-up (lane-wise ray_is_finite and safe_inverse): the inverse direction,
// the finite lanes, and the lanes whose direction is negative on each axis (their near box rows).
// Returns 1 when all rays share one octant.
MCL_INLINE int packet_ray_setup(vfloat3 o, vfloat3 d, vfloat3* inv, vmask* finite, vmask* nx, vmask* ny,
                                vmask* nz) {
  vfloat z = (o.x - o.x) + (o.y - o.y) + (o.z - o.z) + (d.x - d.x) + (d.y - d.y) + (d.z - d.z);
  *finite = z == 0.0f;
  *inv = v3_make(vsel(d.x != 0.0f, 1.0f / d.x, copysign(v_f(INFINITY), d.x)),
                 vsel(d.y != 0.0f, 1.0f / d.y, copysign(v_f(INFINITY), d.y)),
                 vsel(d.z != 0.0f, 1.0f / d.z, copysign(v_f(INFINITY), d.z)));
  *nx = inv->x < 0.0f;
  *ny = inv->y < 0.0f;
  *nz = inv->z < 0.0f;
  return (v_all(*nx) || v_all(v_not(*nx))) && (v_all(*ny) || v_all(v_not(*ny))) &&
         (v_all(*nz) || v_all(v_not(*nz)));
}

// Triangle j against every lane's ray (ray_triangle4's operations in the same order, per lane):
// returns t, with u, v and the lanes whose test fails whatever t is (a degenerate determinant or
// barycentrics outside the triangle) through the pointers.
MCL_INLINE vfloat v_ray_triangle(MCL_GLOBAL const Triangle* tris, uint j, vfloat3 o, vfloat3 d, vfloat* uo,
                                 vfloat* vo, vmask* bad) {
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
  *bad = (fabs(det) < 1e-30f) | (u < 0.0f) | (u > 1.0f) | (v < 0.0f) | ((u + v) > 1.0f);
  *uo = u;
  *vo = v;
  return (te2.x * qx + te2.y * qy + te2.z * qz) * idet;
}

// The lanes of cand whose hit on triangle j (barycentrics u, v per lane; rays o + t d) exists: all
// of them unless alpha is set and j is alpha-tested (MCL_ATTR_ALPHA), then those passing its alpha
// test (alpha_hit_exists, lane by lane: the same test the single-ray leaves make, at the same u, v
// and ray bits).
MCL_INLINE vmask v_alpha_hits(const AlphaScene* alpha, MCL_GLOBAL const Triangle* tris, uint j, vmask cand,
                              vfloat u, vfloat v, vfloat3 o, vfloat3 d) {
  if (!alpha || !(as_uint(tris[j].e2.w) & MCL_ATTR_ALPHA)) return cand;
  float su[MCL_LANES] MCL_LANE_ALIGN, sv[MCL_LANES] MCL_LANE_ALIGN;
  float ox[MCL_LANES] MCL_LANE_ALIGN, oy[MCL_LANES] MCL_LANE_ALIGN, oz[MCL_LANES] MCL_LANE_ALIGN;
  float dx[MCL_LANES] MCL_LANE_ALIGN, dy[MCL_LANES] MCL_LANE_ALIGN, dz[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(u, su);
  v_store_lanes(v, sv);
  v3_store_lanes(o, ox, oy, oz);
  v3_store_lanes(d, dx, dy, dz);
  uint bits = v_bits(cand), gone = 0u;
  while (bits != 0u) {
    uint k = mcl_ctz(bits);
    bits &= bits - 1u;
    if (!alpha_hit_exists(alpha, tris, j, su[k], sv[k], make_float3(ox[k], oy[k], oz[k]), make_float3(dx[k], dy[k], dz[k])))
      gone |= 1u << k;
  }
  return gone == 0u ? cand : cand & v_not(v_from_bits(gone));
}

// Lanes entering child c of node n (the slab test of wide_entry, per lane, each lane with its
// own near and far rows: nx, ny, nz set where the direction is negative) among those in m, at or
// before *tmax; their entry distances through tmin.
MCL_INLINE vmask v_child_entry(MCL_GLOBAL const WideNode* n, uint c, vfloat3 o, vfloat3 inv, vmask nx, vmask ny,
                               vmask nz, vmask m, vfloat tmax, vfloat* tminOut) {
  vfloat bx0 = v_f(n->bounds[0][c]), bx1 = v_f(n->bounds[1][c]);
  vfloat by0 = v_f(n->bounds[2][c]), by1 = v_f(n->bounds[3][c]);
  vfloat bz0 = v_f(n->bounds[4][c]), bz1 = v_f(n->bounds[5][c]);
  vfloat tnx = (vsel(nx, bx1, bx0) - o.x) * inv.x;
  vfloat tfx = (vsel(nx, bx0, bx1) - o.x) * inv.x;
  vfloat tny = (vsel(ny, by1, by0) - o.y) * inv.y;
  vfloat tfy = (vsel(ny, by0, by1) - o.y) * inv.y;
  vfloat tnz = (vsel(nz, bz1, bz0) - o.z) * inv.z;
  vfloat tfz = (vsel(nz, bz0, bz1) - o.z) * inv.z;
  vfloat tmin = v_max_nan1(tnx, v_max_nan1(tny, v_max_nan1(tnz, v_f(0.0f))));
  vfloat tmx = v_min_nan1(tfx, v_min_nan1(tfy, v_min_nan1(tfz, tmax)));
  *tminOut = tmin;
  return m & (tmin <= tmx);
}

// A popped entry entered by at most this many of the packet's rays is traversed ray by ray: in a
// large tree (MCL_PACKET_SWITCH), and in a small one (FrameParams::packetAllRays), where a packet's
// rays enter most nodes anyway and the single-ray traversals' set-up costs more than the lanes
// the packet's tests waste (MCL_PACKET_SWITCH_SMALL; bench/journal/lanes.md, "Packet switch").
#ifndef MCL_PACKET_SWITCH
#define MCL_PACKET_SWITCH 8
#endif
#ifndef MCL_PACKET_SWITCH_SMALL
#define MCL_PACKET_SWITCH_SMALL 2
#endif
MCL_INLINE uint packet_switch(MCL_CONSTANT const FrameParams* f) {
  return f->packetAllRays ? MCL_PACKET_SWITCH_SMALL : MCL_PACKET_SWITCH;
}

// The lanes set in bits traverse node ref's subtree one by one (the single-ray steps, the same box
// and triangle arithmetic), their hit state in the packet's vectors updated lane by lane.
MCL_INLINE void packet_lanes_subtree(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                     const AlphaScene* alpha, vfloat3 o, vfloat3 d, uint ref, uint bits, vfloat* ht, vuint* hcanon, vfloat* hu,
                                     vfloat* hv) {
  float ox[MCL_LANES] MCL_LANE_ALIGN, oy[MCL_LANES] MCL_LANE_ALIGN, oz[MCL_LANES] MCL_LANE_ALIGN;
  float dx[MCL_LANES] MCL_LANE_ALIGN, dy[MCL_LANES] MCL_LANE_ALIGN, dz[MCL_LANES] MCL_LANE_ALIGN;
  float st[MCL_LANES] MCL_LANE_ALIGN, su[MCL_LANES] MCL_LANE_ALIGN, sv[MCL_LANES] MCL_LANE_ALIGN;
  uint scanon[MCL_LANES] MCL_LANE_ALIGN;
  v3_store_lanes(o, ox, oy, oz);
  v3_store_lanes(d, dx, dy, dz);
  v_store_lanes(*ht, st);
  v_store_lanes(*hu, su);
  v_store_lanes(*hv, sv);
  v_store_lanes(*hcanon, scanon);
  while (bits != 0u) {
    uint k = mcl_ctz(bits);
    bits &= bits - 1u;
    // wide_closest_hit's steps from node ref on, going on from the lane's hit so far.
    WideClosest w;
    wide_closest_begin(&w, make_float3(ox[k], oy[k], oz[k]), make_float3(dx[k], dy[k], dz[k]), st[k]);
    w.hit.tri = scanon[k];
    w.hit.u = su[k];
    w.hit.v = sv[k];
    w.ref = ref;
    while (wide_closest_step(nodes, tris, alpha, &w)) {
    }
    st[k] = w.hit.t;
    scanon[k] = w.hit.tri;
    su[k] = w.hit.u;
    sv[k] = w.hit.v;
  }
  *ht = v_loadf_lanes(st);
  *hu = v_loadf_lanes(su);
  *hv = v_loadf_lanes(sv);
  *hcanon = v_loadu_lanes(scanon);
}

// The rays (origin o, inverse direction inv from safe_inverse, per lane) of the lanes set in act,
// nx, ny, nz set where a lane's direction is negative (its near rows, as in make_ray_box_ctx).
// *ht holds each ray's tmax on entry; on return t, canonical slot, u, v of each active lane's hit
// (hcanon MCL_NO_HIT and t unchanged on a miss); alpha (may be null) removes cut-out hits as the
// single-ray traversals do. An entry at most switchAt rays enter goes on ray
// by ray (packet_switch).
MCL_INLINE void packet_closest_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                   const AlphaScene* alpha, vfloat3 o, vfloat3 d, vfloat3 inv, vmask act, vmask nx, vmask ny,
                                   vmask nz, uint switchAt, vfloat* ht, vuint* hcanon, vfloat* hu, vfloat* hv) {
  uint stackRef[MCL_WIDE_STACK_SIZE], stackBits[MCL_WIDE_STACK_SIZE];
  float stackKey[MCL_WIDE_STACK_SIZE];
  vfloat stackDist[MCL_WIDE_STACK_SIZE];  // each ray's entry distance (culls it on pop once a hit is nearer)
  uint sp = 0;
  uint ref = 0u;
  vmask m = act;
  for (;;) {
    if (ref == MCL_WIDE_EMPTY) {
    } else if (ref & MCL_WIDE_LEAF) {
      uint firstTri = wide_leaf_first(ref), last = firstTri + wide_leaf_count(ref) - 1u;
      for (uint j = firstTri; j <= last; ++j) {
        vfloat u, v;
        vmask bad;
        vfloat t = v_ray_triangle(tris, j, o, d, &u, &v, &bad);
        // hit_before per lane: nearer, or at the same t (a hit so far) a lower canonical slot.
        vmask hitc = m & v_not(bad) & (t > 0.0f);
        vmask nearer = hitc & (t < *ht);
        vmask tie = hitc & (t == *ht) & (*hcanon != MCL_NO_HIT);
        if (!v_any(nearer | tie)) continue;
        vmask exists = v_alpha_hits(alpha, tris, j, nearer | tie, u, v, o, d);
        nearer = nearer & exists;
        tie = tie & exists;
        uint canon = as_uint(tris[j].e1.w);
        vmask take = nearer | (tie & (v_u(canon) < *hcanon));
        *ht = vsel(take, t, *ht);
        *hcanon = vsel(take, v_u(canon), *hcanon);
        *hu = vsel(take, u, *hu);
        *hv = vsel(take, v, *hv);
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      uint base = sp, top = sp, entered = 0u;
      for (uint c = 0; c < MCL_WIDE_WIDTH; ++c) {
        uint child = n->child[c];
        if (child == MCL_WIDE_EMPTY) continue;
        vfloat tmin;
        vmask in = v_child_entry(n, c, o, inv, nx, ny, nz, m, *ht, &tmin);
        if (!v_any(in)) continue;
        entered |= 1u << c;
        stackRef[top] = child;
        stackBits[top] = v_bits(in);
        stackKey[top] = v_hmin(vsel(in, tmin, v_f(INFINITY)));
        stackDist[top] = tmin;
        ++top;
      }
      wide_prefetch_children(nodes, tris, n, entered);
      // Farthest key deepest (insertion sort of the run; stable, the lower child nearer the top).
      for (uint p = base + 1u; p < top; ++p) {
        float dk = stackKey[p];
        uint rk = stackRef[p], bk = stackBits[p];
        vfloat ek = stackDist[p];
        uint b = p;
        for (; b > base && stackKey[b - 1u] <= dk; --b) {
          stackKey[b] = stackKey[b - 1u];
          stackRef[b] = stackRef[b - 1u];
          stackBits[b] = stackBits[b - 1u];
          stackDist[b] = stackDist[b - 1u];
        }
        stackKey[b] = dk;
        stackRef[b] = rk;
        stackBits[b] = bk;
        stackDist[b] = ek;
      }
      sp = top;
    }
    // Pop the next entry that some of its rays still enter at or before their nearest hit; one
    // that few rays enter is traversed ray by ray (the packet's box tests would test mostly
    // inactive lanes: incoherent bounce rays part ways a few levels down).
    int found = 0;
    while (sp > 0u) {
      --sp;
      m = v_from_bits(stackBits[sp]) & (stackDist[sp] <= *ht);
      uint bits = v_bits(m);
      if (bits == 0u) continue;
      if (popcount(bits) > switchAt) {
        ref = stackRef[sp];
        found = 1;
        break;
      }
      packet_lanes_subtree(nodes, tris, alpha, o, d, stackRef[sp], bits, ht, hcanon, hu, hv);
    }
    if (!found) return;
  }
}
#endif
