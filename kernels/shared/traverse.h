// traverse.h: closest-hit and any-hit traversal of the flattened BVH with an explicit stack.
// Reads nodes and triangles; pure, so the host reference traversal is this same code.
//
// Speed notes (the kernels run one scalar work item per ray on CPU OpenCL): a node is read as two
// float4 loads (min | leftFirst, max | triCount) and its six plane distances come from two float4
// subtract-multiplies; the near/far planes per axis are picked once per ray by a lane mask instead
// of per node; the nearer child is chosen with selects, not a data-dependent swap; closest hit
// keeps each pushed node's entry distance and skips it on pop once a hit is nearer.
#pragma once
#include "geometry.h"

#ifdef MCL_OPENCL
typedef int4 mcl_mask4;
MCL_INLINE float4 mcl_load4(MCL_GLOBAL const float* p) { return vload4(0, p); }
// b where the mask lane is set (all bits), else a.
MCL_INLINE float4 mcl_select4(float4 a, float4 b, mcl_mask4 m) { return select(a, b, m); }
MCL_INLINE mcl_mask4 mcl_negative_mask(float3 v) {
  return (int4)(v.x < 0.0f ? -1 : 0, v.y < 0.0f ? -1 : 0, v.z < 0.0f ? -1 : 0, 0);
}
#else
typedef glm::bvec4 mcl_mask4;
inline float4 mcl_load4(const float* p) {
  float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline float4 mcl_select4(float4 a, float4 b, mcl_mask4 m) {
  return float4(m.x ? b.x : a.x, m.y ? b.y : a.y, m.z ? b.z : a.z, m.w ? b.w : a.w);
}
inline mcl_mask4 mcl_negative_mask(float3 v) {
  return mcl_mask4(v.x < 0.0f, v.y < 0.0f, v.z < 0.0f, false);
}
#endif

// Per-ray constants of the slab test (w lanes 0 and unused).
typedef struct {
  float4 org;
  float4 invDir;
  mcl_mask4 neg;  // lanes whose direction is negative: their near plane is the box's max
} RayBoxCtx;

MCL_INLINE RayBoxCtx make_ray_box_ctx(float3 org, float3 dir) {
  RayBoxCtx c;
  float3 inv = safe_inverse(dir);
  c.org = with_w(org, 0.0f);
  c.invDir = with_w(inv, 0.0f);
  c.neg = mcl_negative_mask(inv);
  return c;
}

// Entry distance of node n (see ray_box: same planes, same operations, same result), or INFINITY.
MCL_INLINE float node_entry(MCL_GLOBAL const BvhNode* n, const RayBoxCtx* c, float tmax) {
  MCL_GLOBAL const float* p = (MCL_GLOBAL const float*)n;
  float4 lo = mcl_load4(p);
  float4 hi = mcl_load4(p + 4);
  lo.w = 0.0f;  // uint bits there: small ones are denormals, which cost a microcode assist each
  hi.w = 0.0f;
  float4 tn = (mcl_select4(lo, hi, c->neg) - c->org) * c->invDir;
  float4 tf = (mcl_select4(hi, lo, c->neg) - c->org) * c->invDir;
  return slab_entry(tn.x, tn.y, tn.z, tf.x, tf.y, tf.z, tmax);
}

// Closest hit along org + t*dir for t in (0, tmax).
MCL_INLINE Hit bvh_closest_hit(MCL_GLOBAL const BvhNode* nodes, MCL_GLOBAL const Triangle* tris,
                               float3 org, float3 dir, float tmax) {
  Hit hit;
  hit.t = tmax;
  hit.tri = MCL_NO_HIT;
  hit.u = 0.0f;
  hit.v = 0.0f;
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  uint stack[MCL_BVH_STACK_SIZE];
  float stackT[MCL_BVH_STACK_SIZE];  // entry distance of each stacked node
  uint sp = 0;
  uint node = 0;
  if (node_entry(&nodes[0], &ctx, hit.t) == INFINITY) {
    hit.t = INFINITY;  // a miss reads t = INFINITY whichever way it is found
    return hit;
  }
  for (;;) {
    MCL_GLOBAL const BvhNode* n = &nodes[node];
    uint first = n->leftFirst, count = n->triCount;
    if (count > 0) {
      for (uint ti = first; ti < first + count; ++ti) {
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
      // Visit the nearer child first; push the farther one if the ray enters it.
      float da = node_entry(&nodes[first], &ctx, hit.t);
      float db = node_entry(&nodes[first + 1], &ctx, hit.t);
      int bFirst = db < da;
      uint nearC = bFirst ? first + 1 : first;
      uint farC = bFirst ? first : first + 1;
      float dNear = bFirst ? db : da;
      float dFar = bFirst ? da : db;
      if (dNear != INFINITY) {
        if (dFar != INFINITY && sp < MCL_BVH_STACK_SIZE) {
          stack[sp] = farC;
          stackT[sp] = dFar;
          ++sp;
        }
        node = nearC;
        continue;
      }
    }
    // Pop the next node the ray still enters before the closest hit so far.
    for (;;) {
      if (sp == 0) {
        if (hit.tri == MCL_NO_HIT) hit.t = INFINITY;
        return hit;
      }
      --sp;
      if (stackT[sp] <= hit.t) break;
    }
    node = stack[sp];
  }
}

// 1 if any triangle intersects org + t*dir for t in (0, tmax), else 0. Stops at the first hit.
MCL_INLINE int bvh_any_hit(MCL_GLOBAL const BvhNode* nodes, MCL_GLOBAL const Triangle* tris,
                           float3 org, float3 dir, float tmax) {
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  uint stack[MCL_BVH_STACK_SIZE];
  uint sp = 0;
  uint node = 0;
  if (node_entry(&nodes[0], &ctx, tmax) == INFINITY) return 0;
  for (;;) {
    MCL_GLOBAL const BvhNode* n = &nodes[node];
    uint first = n->leftFirst, count = n->triCount;
    if (count > 0) {
      for (uint ti = first; ti < first + count; ++ti) {
        float u = 0.0f, v = 0.0f;
        if (ray_triangle(org, dir, xyz(tris[ti].v0), xyz(tris[ti].e1), xyz(tris[ti].e2), tmax, &u,
                         &v) < tmax)
          return 1;
      }
    } else {
      float da = node_entry(&nodes[first], &ctx, tmax);
      float db = node_entry(&nodes[first + 1], &ctx, tmax);
      int bFirst = db < da;
      uint nearC = bFirst ? first + 1 : first;
      uint farC = bFirst ? first : first + 1;
      float dNear = bFirst ? db : da;
      float dFar = bFirst ? da : db;
      if (dNear != INFINITY) {
        if (dFar != INFINITY && sp < MCL_BVH_STACK_SIZE) stack[sp++] = farC;
        node = nearC;
        continue;
      }
    }
    if (sp == 0) return 0;
    node = stack[--sp];
  }
}
