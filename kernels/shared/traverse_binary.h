// traverse_binary.h: closest-hit and any-hit traversal of the binary BVH (BvhNode, Bvh::nodes)
// with a short explicit stack: the layout for GPUs (--bvh-layout binary). Reads nodes and
// triangles; pure, so the host reference traversal is this same code.
//
// An interior node's two children are adjacent (leftFirst, leftFirst + 1), so a visit reads their
// boxes as one 64-byte block, a two-child-box node, and tests both with ray_box. The nearer
// entered child (the left one on a tie) is visited next and the farther one pushed; closest hit
// keeps each entry's distance and skips it on pop once a hit is nearer. One entry per level at
// most: the stack never holds more than the depth (< MCL_BVH_STACK_SIZE). Leaf triangles are
// tested one by one with ray_triangle, whose operations ray_triangle4 repeats lane-wise, so both
// layouts compute the same t, u and v for a triangle.
#pragma once
#include "geometry.h"
#include "surface_texture.h"
#include "traverse_stack.h"

// Entry distance of node n's box (ray_box), INFINITY when missed or entered beyond tmax.
MCL_INLINE float binary_entry(MCL_GLOBAL const BvhNode* n, float3 org, float3 inv, float tmax) {
  return ray_box(org, inv, make_float3(n->minX, n->minY, n->minZ),
                 make_float3(n->maxX, n->maxY, n->maxZ), tmax);
}

// Closest hit along org + t*dir for t in (0, tmax); alpha (may be null) removes the hits that
// fail their material's alpha test (surface_texture.h).
MCL_INLINE Hit binary_closest_hit(MCL_GLOBAL const BvhNode* nodes, MCL_GLOBAL const Triangle* tris,
                                  const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  Hit hit;
  hit.t = tmax;
  hit.tri = MCL_NO_HIT;
  hit.u = 0.0f;
  hit.v = 0.0f;
  float3 inv = safe_inverse(dir);
  uint stack[MCL_BVH_STACK_SIZE];
  float stackT[MCL_BVH_STACK_SIZE];  // entry distance of each stacked node
  uint sp = 0;
  uint ref = 0;
  // A non-finite ray (ray_is_finite) is a miss: it would "enter" every box.
  if (!ray_is_finite(org, dir) || binary_entry(&nodes[0], org, inv, tmax) == INFINITY) {
    hit.t = INFINITY;
    return hit;
  }
  for (;;) {
    MCL_GLOBAL const BvhNode* n = &nodes[ref];
    if (n->triCount > 0) {
      for (uint i = n->leftFirst, end = n->leftFirst + n->triCount; i < end; ++i) {
        float u = 0.0f, v = 0.0f;
        float t = ray_triangle(org, dir, xyz(tris[i].v0), xyz(tris[i].e1), xyz(tris[i].e2),
                               leaf_tmax(hit.t, hit.tri), &u, &v);
        uint canon = as_uint(tris[i].e1.w);
        if (hit_before(t, canon, hit.t, hit.tri) && alpha_hit_exists(alpha, tris, i, u, v, org, dir)) {
          hit.t = t;
          hit.tri = canon;  // the canonical slot, whichever copy was hit
          hit.u = u;
          hit.v = v;
        }
      }
    } else {
      uint l = n->leftFirst;
      float dl = binary_entry(&nodes[l], org, inv, hit.t);
      float dr = binary_entry(&nodes[l + 1u], org, inv, hit.t);
      int rightFirst = dr < dl;
      float dNear = rightFirst ? dr : dl, dFar = rightFirst ? dl : dr;
      if (dNear != INFINITY) {
        stack[sp] = rightFirst ? l : l + 1u;
        stackT[sp] = dFar;
        sp += dFar != INFINITY;
        ref = rightFirst ? l + 1u : l;
        continue;
      }
    }
    if (!pop_entered(stack, stackT, &sp, hit.t, &ref)) {
      if (hit.tri == MCL_NO_HIT) hit.t = INFINITY;
      return hit;
    }
  }
}

// 1 if any triangle intersects org + t*dir for t in (0, tmax) (and passes the alpha test when
// alpha is not null), else 0. Stops at the first hit.
MCL_INLINE int binary_any_hit(MCL_GLOBAL const BvhNode* nodes, MCL_GLOBAL const Triangle* tris,
                              const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  float3 inv = safe_inverse(dir);
  uint stack[MCL_BVH_STACK_SIZE];
  uint sp = 0;
  uint ref = 0;
  if (!ray_is_finite(org, dir) || binary_entry(&nodes[0], org, inv, tmax) == INFINITY) return 0;
  for (;;) {
    MCL_GLOBAL const BvhNode* n = &nodes[ref];
    if (n->triCount > 0) {
      for (uint i = n->leftFirst, end = n->leftFirst + n->triCount; i < end; ++i) {
        float u = 0.0f, v = 0.0f;
        if (ray_triangle(org, dir, xyz(tris[i].v0), xyz(tris[i].e1), xyz(tris[i].e2), tmax, &u,
                         &v) < tmax &&
            alpha_hit_exists(alpha, tris, i, u, v, org, dir))
          return 1;
      }
    } else {
      uint l = n->leftFirst;
      float dl = binary_entry(&nodes[l], org, inv, tmax);
      float dr = binary_entry(&nodes[l + 1u], org, inv, tmax);
      int rightFirst = dr < dl;
      float dNear = rightFirst ? dr : dl, dFar = rightFirst ? dl : dr;
      if (dNear != INFINITY) {
        stack[sp] = rightFirst ? l : l + 1u;
        sp += dFar != INFINITY;
        ref = rightFirst ? l + 1u : l;
        continue;
      }
    }
    if (sp == 0) return 0;
    ref = stack[--sp];
  }
}
