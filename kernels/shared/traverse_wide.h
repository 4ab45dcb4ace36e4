// traverse_wide.h: closest-hit and any-hit traversal of the 4-wide BVH (WideNode, Bvh::wide) with
// an explicit stack: the layout for CPUs (--bvh-layout wide). Reads nodes and triangles; pure, so
// the host reference traversal is this same code.
//
// Speed notes (the kernels run one scalar work item per ray on CPU OpenCL, and PoCL cannot
// vectorise across work items because traversal diverges): a node's four child boxes are tested at
// once with float4 arithmetic inside the work item (SSE/AVX lanes); the near and far rows per axis
// are picked once per ray as row indices instead of per node; the hit children are ordered nearest
// first by a five-comparator sorting network on their entry distances (misses are INFINITY and sort
// last); closest hit keeps each pushed entry's distance and skips it on pop once a hit is nearer;
// any-hit returns at the first hit. Child refs live in uint fields, never in float lanes.
#pragma once
#include "geometry.h"

#ifdef MCL_OPENCL
MCL_INLINE float4 mcl_splat4(float x) { return (float4)(x); }
// Lane-wise mcl_max_nan1 / mcl_min_nan1 (a NaN in the first operand yields the second).
MCL_INLINE float4 mcl_max4_nan1(float4 a, float4 b) { return select(b, a, a > b); }
MCL_INLINE float4 mcl_min4_nan1(float4 a, float4 b) { return select(b, a, a < b); }
// tmin where tmin <= tmax, else INFINITY.
MCL_INLINE float4 mcl_entry4(float4 tmin, float4 tmax) {
  return select((float4)(INFINITY), tmin, tmin <= tmax);
}
// t where ray_triangle's tests pass (the same comparisons, NaNs included), else INFINITY. The
// relational built-ins, not the operators: Oclgrind (21.10) got the operator form of these masks
// wrong (shadow rays at a light's distance disagreed with PoCL and the host); same code on PoCL.
MCL_INLINE float4 mcl_tri_t4(float4 det, float4 u, float4 v, float4 t, float tmax) {
  const float4 zero = (float4)(0.0f), one = (float4)(1.0f);
  int4 bad = isless(fabs(det), (float4)(1e-30f)) | isless(u, zero) | isgreater(u, one) |
             isless(v, zero) | isgreater(u + v, one);
  int4 ok = ~bad & isgreater(t, zero) & isless(t, (float4)(tmax));
  return select((float4)(INFINITY), t, ok);
}
#else
inline float mcl_tri_t1(float det, float u, float v, float t, float tmax) {
  bool bad = fabs(det) < 1e-30f || u < 0.0f || u > 1.0f || v < 0.0f || u + v > 1.0f;
  return (!bad && t > 0.0f && t < tmax) ? t : INFINITY;
}
inline float4 mcl_tri_t4(float4 det, float4 u, float4 v, float4 t, float tmax) {
  return float4(mcl_tri_t1(det.x, u.x, v.x, t.x, tmax), mcl_tri_t1(det.y, u.y, v.y, t.y, tmax),
                mcl_tri_t1(det.z, u.z, v.z, t.z, tmax), mcl_tri_t1(det.w, u.w, v.w, t.w, tmax));
}
inline float4 mcl_splat4(float x) { return float4(x); }
inline float4 mcl_max4_nan1(float4 a, float4 b) {
  return float4(mcl_max_nan1(a.x, b.x), mcl_max_nan1(a.y, b.y), mcl_max_nan1(a.z, b.z),
                mcl_max_nan1(a.w, b.w));
}
inline float4 mcl_min4_nan1(float4 a, float4 b) {
  return float4(mcl_min_nan1(a.x, b.x), mcl_min_nan1(a.y, b.y), mcl_min_nan1(a.z, b.z),
                mcl_min_nan1(a.w, b.w));
}
inline float4 mcl_entry4(float4 tmin, float4 tmax) {
  return float4(tmin.x <= tmax.x ? tmin.x : INFINITY, tmin.y <= tmax.y ? tmin.y : INFINITY,
                tmin.z <= tmax.z ? tmin.z : INFINITY, tmin.w <= tmax.w ? tmin.w : INFINITY);
}
#endif

// Per-ray constants of the four-box slab test: origin and inverse direction splatted per axis, and
// the WideNode::bounds row of each axis's near and far plane (the max row where the direction is
// negative, -0 included, as in ray_box).
typedef struct {
  float4 ox, oy, oz;
  float4 ix, iy, iz;
  uint nearX, farX, nearY, farY, nearZ, farZ;
} RayBoxCtx;

MCL_INLINE RayBoxCtx make_ray_box_ctx(float3 org, float3 dir) {
  RayBoxCtx c;
  float3 inv = safe_inverse(dir);
  c.ox = mcl_splat4(org.x);
  c.oy = mcl_splat4(org.y);
  c.oz = mcl_splat4(org.z);
  c.ix = mcl_splat4(inv.x);
  c.iy = mcl_splat4(inv.y);
  c.iz = mcl_splat4(inv.z);
  c.nearX = inv.x < 0.0f ? 1u : 0u;
  c.farX = 1u - c.nearX;
  c.nearY = inv.y < 0.0f ? 3u : 2u;
  c.farY = 5u - c.nearY;
  c.nearZ = inv.z < 0.0f ? 5u : 4u;
  c.farZ = 9u - c.nearZ;
  return c;
}

// Entry distances of the four children of n (same planes, operations and result as ray_box per
// child), INFINITY for the children the ray misses or enters beyond tmax.
MCL_INLINE float4 wide_entry(MCL_GLOBAL const WideNode* n, const RayBoxCtx* c, float tmax) {
  float4 tnx = (n->bounds[c->nearX] - c->ox) * c->ix;
  float4 tfx = (n->bounds[c->farX] - c->ox) * c->ix;
  float4 tny = (n->bounds[c->nearY] - c->oy) * c->iy;
  float4 tfy = (n->bounds[c->farY] - c->oy) * c->iy;
  float4 tnz = (n->bounds[c->nearZ] - c->oz) * c->iz;
  float4 tfz = (n->bounds[c->farZ] - c->oz) * c->iz;
  float4 tmin = mcl_max4_nan1(tnx, mcl_max4_nan1(tny, mcl_max4_nan1(tnz, mcl_splat4(0.0f))));
  float4 tmx = mcl_min4_nan1(tfx, mcl_min4_nan1(tfy, mcl_min4_nan1(tfz, mcl_splat4(tmax))));
  return mcl_entry4(tmin, tmx);
}

// Compare-exchange of (distance, ref) pairs by distance, with selects (no data-dependent branch).
#define MCL_CSWAP(da, ra, db, rb)            \
  {                                          \
    int s_ = (db) < (da);                    \
    float dt_ = s_ ? (db) : (da);            \
    uint rt_ = s_ ? (rb) : (ra);             \
    (db) = s_ ? (da) : (db);                 \
    (rb) = s_ ? (ra) : (rb);                 \
    (da) = dt_;                              \
    (ra) = rt_;                              \
  }

// Sorts four (distance, ref) pairs by distance: a 5-comparator network, nearest first.
#define MCL_SORT4(d0, r0, d1, r1, d2, r2, d3, r3) \
  {                                               \
    MCL_CSWAP(d0, r0, d1, r1);                    \
    MCL_CSWAP(d2, r2, d3, r3);                    \
    MCL_CSWAP(d0, r0, d2, r2);                    \
    MCL_CSWAP(d1, r1, d3, r3);                    \
    MCL_CSWAP(d1, r1, d2, r2);                    \
  }


// Moller-Trumbore (ray_triangle's operations in the same order, lane-wise) against triangles
// tris[first + i], i < 4, the indices clamped to last (a repeated triangle repeats its t in a later
// lane, which never wins a tie). Returns t per lane (INFINITY on a miss); u, v through the pointers.
MCL_INLINE float4 ray_triangle4(MCL_GLOBAL const Triangle* tris, uint first, uint last, float3 org,
                                float3 dir, float tmax, float4* uOut, float4* vOut) {
  uint i1 = first + 1u < last ? first + 1u : last, i2 = first + 2u < last ? first + 2u : last;
  uint i3 = first + 3u < last ? first + 3u : last;
  float4 a0 = tris[first].v0, a1 = tris[i1].v0, a2 = tris[i2].v0, a3 = tris[i3].v0;
  float4 b0 = tris[first].e1, b1 = tris[i1].e1, b2 = tris[i2].e1, b3 = tris[i3].e1;
  float4 c0 = tris[first].e2, c1 = tris[i1].e2, c2 = tris[i2].e2, c3 = tris[i3].e2;
  float4 v0x = make_float4(a0.x, a1.x, a2.x, a3.x), v0y = make_float4(a0.y, a1.y, a2.y, a3.y),
         v0z = make_float4(a0.z, a1.z, a2.z, a3.z);
  float4 e1x = make_float4(b0.x, b1.x, b2.x, b3.x), e1y = make_float4(b0.y, b1.y, b2.y, b3.y),
         e1z = make_float4(b0.z, b1.z, b2.z, b3.z);
  float4 e2x = make_float4(c0.x, c1.x, c2.x, c3.x), e2y = make_float4(c0.y, c1.y, c2.y, c3.y),
         e2z = make_float4(c0.z, c1.z, c2.z, c3.z);
  float4 px = dir.y * e2z - e2y * dir.z;  // cross(dir, e2)
  float4 py = dir.z * e2x - e2z * dir.x;
  float4 pz = dir.x * e2y - e2x * dir.y;
  float4 det = e1x * px + e1y * py + e1z * pz;
  float4 inv = 1.0f / det;
  float4 sx = org.x - v0x, sy = org.y - v0y, sz = org.z - v0z;
  float4 u = (sx * px + sy * py + sz * pz) * inv;
  float4 qx = sy * e1z - e1y * sz;  // cross(s, e1)
  float4 qy = sz * e1x - e1z * sx;
  float4 qz = sx * e1y - e1x * sy;
  float4 v = (dir.x * qx + dir.y * qy + dir.z * qz) * inv;
  float4 t = (e2x * qx + e2y * qy + e2z * qz) * inv;
  *uOut = u;
  *vOut = v;
  return mcl_tri_t4(det, u, v, t, tmax);
}

MCL_INLINE uint wide_leaf_first(uint ref) { return (ref & ~MCL_WIDE_LEAF) >> 4; }
MCL_INLINE uint wide_leaf_count(uint ref) { return (ref & 15u) + 1u; }

// Closest hit along org + t*dir for t in (0, tmax).
MCL_INLINE Hit wide_closest_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                float3 org, float3 dir, float tmax) {
  Hit hit;
  hit.t = tmax;
  hit.tri = MCL_NO_HIT;
  hit.u = 0.0f;
  hit.v = 0.0f;
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  uint stack[MCL_WIDE_STACK_SIZE];
  float stackT[MCL_WIDE_STACK_SIZE];  // entry distance of each stacked child
  uint sp = 0;
  uint ref = 0;  // the root is wide node 0
  for (;;) {
    if (ref & MCL_WIDE_LEAF) {
      uint first = wide_leaf_first(ref), last = first + wide_leaf_count(ref) - 1u;
      for (uint b = first; b <= last; b += 4u) {
        float4 u, v;
        float4 t = ray_triangle4(tris, b, last, org, dir, hit.t, &u, &v);
        // The nearest lane, the lowest on a tie (as the triangles one by one would find it).
        float bt = t.x, bu = u.x, bv = v.x;
        uint bi = b;
        if (t.y < bt) { bt = t.y; bu = u.y; bv = v.y; bi = b + 1u; }
        if (t.z < bt) { bt = t.z; bu = u.z; bv = v.z; bi = b + 2u; }
        if (t.w < bt) { bt = t.w; bu = u.w; bv = v.w; bi = b + 3u; }
        if (bt < hit.t) {
          hit.t = bt;
          hit.tri = bi;
          hit.u = bu;
          hit.v = bv;
        }
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      float4 d = wide_entry(n, &ctx, hit.t);
      float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
      uint r0 = n->child[0], r1 = n->child[1], r2 = n->child[2], r3 = n->child[3];
      MCL_SORT4(d0, r0, d1, r1, d2, r2, d3, r3);
      if (d0 != INFINITY) {
        // Push the farther hit children (farthest deepest), visit the nearest.
        stack[sp] = r3;
        stackT[sp] = d3;
        sp += d3 != INFINITY;
        stack[sp] = r2;
        stackT[sp] = d2;
        sp += d2 != INFINITY;
        stack[sp] = r1;
        stackT[sp] = d1;
        sp += d1 != INFINITY;
        ref = r0;
        continue;
      }
    }
    // Pop the next child the ray still enters before the closest hit so far.
    for (;;) {
      if (sp == 0) {
        if (hit.tri == MCL_NO_HIT) hit.t = INFINITY;
        return hit;
      }
      --sp;
      if (stackT[sp] <= hit.t) break;
    }
    ref = stack[sp];
  }
}

// 1 if any triangle intersects org + t*dir for t in (0, tmax), else 0. Stops at the first hit.
MCL_INLINE int wide_any_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                            float3 org, float3 dir, float tmax) {
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  uint stack[MCL_WIDE_STACK_SIZE];
  uint sp = 0;
  uint ref = 0;
  for (;;) {
    if (ref & MCL_WIDE_LEAF) {
      uint first = wide_leaf_first(ref), last = first + wide_leaf_count(ref) - 1u;
      for (uint b = first; b <= last; b += 4u) {
        float4 u, v;
        float4 t = ray_triangle4(tris, b, last, org, dir, tmax, &u, &v);
        if (t.x < tmax || t.y < tmax || t.z < tmax || t.w < tmax) return 1;
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      float4 d = wide_entry(n, &ctx, tmax);
      float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
      uint r0 = n->child[0], r1 = n->child[1], r2 = n->child[2], r3 = n->child[3];
      MCL_SORT4(d0, r0, d1, r1, d2, r2, d3, r3);
      if (d0 != INFINITY) {
        stack[sp] = r3;
        sp += d3 != INFINITY;
        stack[sp] = r2;
        sp += d2 != INFINITY;
        stack[sp] = r1;
        sp += d1 != INFINITY;
        ref = r0;
        continue;
      }
    }
    if (sp == 0) return 0;
    ref = stack[--sp];
  }
}
