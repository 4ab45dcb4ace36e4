// traverse.h: closest-hit and any-hit traversal of the 4-wide BVH (WideNode) with an explicit
// stack. Reads nodes and triangles; pure, so the host reference traversal is this same code.
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
#else
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

MCL_INLINE uint wide_leaf_first(uint ref) { return (ref & ~MCL_WIDE_LEAF) >> 4; }
MCL_INLINE uint wide_leaf_count(uint ref) { return (ref & 15u) + 1u; }

// Closest hit along org + t*dir for t in (0, tmax).
MCL_INLINE Hit bvh_closest_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
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
      uint first = wide_leaf_first(ref), end = first + wide_leaf_count(ref);
      for (uint ti = first; ti < end; ++ti) {
        float u = 0.0f, v = 0.0f;
        float t = ray_triangle(org, dir, xyz(tris[ti].v0), xyz(tris[ti].e1), xyz(tris[ti].e2),
                               hit.t, &u, &v);
        if (t < hit.t) {
          hit.t = t;
          hit.tri = ti;
          hit.u = u;
          hit.v = v;
        }
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      float4 d = wide_entry(n, &ctx, hit.t);
      float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
      uint r0 = n->child[0], r1 = n->child[1], r2 = n->child[2], r3 = n->child[3];
      MCL_CSWAP(d0, r0, d1, r1);
      MCL_CSWAP(d2, r2, d3, r3);
      MCL_CSWAP(d0, r0, d2, r2);
      MCL_CSWAP(d1, r1, d3, r3);
      MCL_CSWAP(d1, r1, d2, r2);
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
MCL_INLINE int bvh_any_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                           float3 org, float3 dir, float tmax) {
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  uint stack[MCL_WIDE_STACK_SIZE];
  uint sp = 0;
  uint ref = 0;
  for (;;) {
    if (ref & MCL_WIDE_LEAF) {
      uint first = wide_leaf_first(ref), end = first + wide_leaf_count(ref);
      for (uint ti = first; ti < end; ++ti) {
        float u = 0.0f, v = 0.0f;
        if (ray_triangle(org, dir, xyz(tris[ti].v0), xyz(tris[ti].e1), xyz(tris[ti].e2), tmax, &u,
                         &v) < tmax)
          return 1;
      }
    } else {
      MCL_GLOBAL const WideNode* n = &nodes[ref];
      float4 d = wide_entry(n, &ctx, tmax);
      float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
      uint r0 = n->child[0], r1 = n->child[1], r2 = n->child[2], r3 = n->child[3];
      MCL_CSWAP(d0, r0, d1, r1);
      MCL_CSWAP(d2, r2, d3, r3);
      MCL_CSWAP(d0, r0, d2, r2);
      MCL_CSWAP(d1, r1, d3, r3);
      MCL_CSWAP(d1, r1, d2, r2);
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
