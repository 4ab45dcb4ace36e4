// traverse_instances.h: closest-hit and any-hit traversal of a two-level 8-wide BVH (reads the
// wide nodes, triangles and Instance records; pure, so the host reference is this same code). The
// top level (wide node 0) is built over the instances' world boxes: its leaf references name
// ranges of the instance array instead of triangles. Entering an instance maps the ray into its
// object space (the direction is not renormalised, so t along it is the world t and the stack's
// distances, the closest hit so far and tmax stay comparable) and traverses its bottom level,
// whose wide nodes and triangles live in the same arrays (indices already rebased); when the
// bottom level's part of the stack is used up the next instance of the leaf is entered, then the
// world ray is restored and the top level goes on.
#pragma once
#include "traverse_wide.h"

// A top and a bottom level, each at most MCL_WIDE_STACK_SIZE entries deep.
#define MCL_INSTANCE_STACK_SIZE (2 * MCL_WIDE_STACK_SIZE)

// A closest hit and the instance (index into the Instance array) whose triangle it is.
typedef struct {
  Hit hit;
  uint instance;  // MCL_NO_INSTANCE on a miss
} InstanceHit;

// Row r . (p, 1) and row r . (d, 0) of a 3x4 affine map, the products summed left to right;
// written once for floats and lanes over the map's rows r0, r1, r2 (P, F3, F4, V: the prefix,
// float3, float4, f3 here; v_, vfloat3, vfloat4, v3 in stages/stage_lanes.h); instance_normal_of:
// the unit normal that the map with these rows (an instance's world-to-object map) transposed
// gives object-space normal n (n need not be unit).
#define MCL_DEFINE_AFFINE(P, F3, F4, V)                                                                   \
  MCL_INLINE F3 P##affine_point_of(F4 r0, F4 r1, F4 r2, F3 p) {                                           \
    return V##_make(r0.x * p.x + r0.y * p.y + r0.z * p.z + r0.w, r1.x * p.x + r1.y * p.y + r1.z * p.z + r1.w, \
                    r2.x * p.x + r2.y * p.y + r2.z * p.z + r2.w);                                         \
  }                                                                                                       \
  MCL_INLINE F3 P##affine_vector_of(F4 r0, F4 r1, F4 r2, F3 d) {                                          \
    return V##_make(r0.x * d.x + r0.y * d.y + r0.z * d.z, r1.x * d.x + r1.y * d.y + r1.z * d.z,           \
                    r2.x * d.x + r2.y * d.y + r2.z * d.z);                                                \
  }                                                                                                       \
  MCL_INLINE F3 P##instance_normal_of(F4 w0, F4 w1, F4 w2, F3 n) {                                        \
    return V##_normalize(V##_make(w0.x * n.x + w1.x * n.y + w2.x * n.z, w0.y * n.x + w1.y * n.y + w2.y * n.z, \
                                  w0.z * n.x + w1.z * n.y + w2.z * n.z));                                 \
  }
MCL_DEFINE_AFFINE(, float3, float4, f3)

MCL_INLINE float3 affine_point(MCL_GLOBAL const float4* rows, float3 p) {
  return affine_point_of(rows[0], rows[1], rows[2], p);
}
MCL_INLINE float3 affine_vector(MCL_GLOBAL const float4* rows, float3 d) {
  return affine_vector_of(rows[0], rows[1], rows[2], d);
}

// Pops entries above stack[base] until one the ray enters at or before tHit (stored in *ref,
// returns 1); returns 0 when only the entries below base are left.
MCL_INLINE int pop_entered_above(const uint* stack, const float* stackT, uint* sp, uint base, float tHit,
                                 uint* ref) {
  while (*sp > base) {
    --*sp;
    if (stackT[*sp] <= tHit) {
      *ref = stack[*sp];
      return 1;
    }
  }
  return 0;
}

// Closest hit along org + t*dir for t in (0, tmax) over every instance; hit.tri is the canonical
// slot of the triangle in the shared array (its bottom level's), instance the Instance entered.
// The leaves are wide_leaf_closest's, so the hit is the first in hit_before's order; two
// placements of one triangle met at exactly the same t keep the one entered first.
MCL_INLINE InstanceHit instances_closest_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                             MCL_GLOBAL const Instance* inst, const AlphaScene* alpha,
                                             float3 org, float3 dir, float tmax) {
  InstanceHit r;
  r.hit.t = tmax;
  r.hit.tri = MCL_NO_HIT;
  r.hit.u = 0.0f;
  r.hit.v = 0.0f;
  r.instance = MCL_NO_INSTANCE;
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  float3 o = org, d = dir;  // the ray in the current level's space
  uint stack[MCL_INSTANCE_STACK_SIZE];
  float stackT[MCL_INSTANCE_STACK_SIZE];
  uint sp = 0, spBase = 0;
  uint cur = MCL_NO_INSTANCE, curEnd = 0;  // the instance being traversed, the end of its leaf's range
  uint ref = ray_is_finite(org, dir) ? 0u : MCL_WIDE_EMPTY;
  for (;;) {
    if (ref == MCL_WIDE_EMPTY) {
      // An empty slot, or a non-finite ray: nothing to test (as in wide_closest_hit).
    } else if ((ref & MCL_WIDE_LEAF) && cur == MCL_NO_INSTANCE) {
      // A top-level leaf: enter its first instance.
      cur = wide_leaf_first(ref);
      curEnd = cur + wide_leaf_count(ref);
      spBase = sp;
      o = affine_point(inst[cur].worldToObject, org);
      d = affine_vector(inst[cur].worldToObject, dir);
      ctx = make_ray_box_ctx(o, d);
      ref = inst[cur].root;
      continue;
    } else if (ref & MCL_WIDE_LEAF) {
      if (wide_leaf_closest(tris, alpha, ref, o, d, &r.hit)) r.instance = cur;
    } else {
      uint next = wide_visit(nodes, tris, ref, &ctx, r.hit.t, stack, stackT, &sp);
      if (next != MCL_WIDE_EMPTY) {
        ref = next;
        continue;
      }
    }
    if (cur != MCL_NO_INSTANCE) {
      if (pop_entered_above(stack, stackT, &sp, spBase, r.hit.t, &ref)) continue;
      cur += 1u;
      if (cur < curEnd) {  // the leaf's next instance
        o = affine_point(inst[cur].worldToObject, org);
        d = affine_vector(inst[cur].worldToObject, dir);
        ctx = make_ray_box_ctx(o, d);
        ref = inst[cur].root;
        continue;
      }
      cur = MCL_NO_INSTANCE;  // back to the top level, in world space
      o = org;
      d = dir;
      ctx = make_ray_box_ctx(org, dir);
    }
    if (!pop_entered(stack, stackT, &sp, r.hit.t, &ref)) {
      if (r.hit.tri == MCL_NO_HIT) r.hit.t = INFINITY;  // tri: already the canonical slot
      return r;
    }
  }
}

// 1 if any instance's triangle intersects org + t*dir for t in (0, tmax) (passing the alpha test
// when alpha is not null), else 0. Stops at the first hit.
MCL_INLINE int instances_any_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                 MCL_GLOBAL const Instance* inst, const AlphaScene* alpha, float3 org,
                                 float3 dir, float tmax) {
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  float3 o = org, d = dir;
  uint stack[MCL_INSTANCE_STACK_SIZE];
  float stackT[MCL_INSTANCE_STACK_SIZE];
  uint sp = 0, spBase = 0;
  uint cur = MCL_NO_INSTANCE, curEnd = 0;
  uint ref = ray_is_finite(org, dir) ? 0u : MCL_WIDE_EMPTY;
  for (;;) {
    if (ref == MCL_WIDE_EMPTY) {
    } else if ((ref & MCL_WIDE_LEAF) && cur == MCL_NO_INSTANCE) {
      cur = wide_leaf_first(ref);
      curEnd = cur + wide_leaf_count(ref);
      spBase = sp;
      o = affine_point(inst[cur].worldToObject, org);
      d = affine_vector(inst[cur].worldToObject, dir);
      ctx = make_ray_box_ctx(o, d);
      ref = inst[cur].root;
      continue;
    } else if (ref & MCL_WIDE_LEAF) {
      uint first = wide_leaf_first(ref), last = first + wide_leaf_count(ref) - 1u;
      for (uint b = first; b <= last; b += 4u) {
        float4 u, v;
        float4 t = ray_triangle4(tris, b, last, o, d, tmax, &u, &v);
        if (alpha) t = alpha_filter4(alpha, tris, b, last, t, u, v, tmax, o, d);
        if (t.x < tmax || t.y < tmax || t.z < tmax || t.w < tmax) return 1;
      }
    } else {
      uint next = wide_visit(nodes, tris, ref, &ctx, tmax, stack, stackT, &sp);
      if (next != MCL_WIDE_EMPTY) {
        ref = next;
        continue;
      }
    }
    if (cur != MCL_NO_INSTANCE) {
      if (sp > spBase) {
        ref = stack[--sp];
        continue;
      }
      cur += 1u;
      if (cur < curEnd) {
        o = affine_point(inst[cur].worldToObject, org);
        d = affine_vector(inst[cur].worldToObject, dir);
        ctx = make_ray_box_ctx(o, d);
        ref = inst[cur].root;
        continue;
      }
      cur = MCL_NO_INSTANCE;
      o = org;
      d = dir;
      ctx = make_ray_box_ctx(org, dir);
    }
    if (sp == 0) return 0;
    ref = stack[--sp];
  }
}
