// traverse.h: closest-hit and any-hit traversal of the flattened BVH with an explicit stack.
// Reads nodes and triangles; pure, so the host reference traversal is this same code.
#pragma once
#include "geometry.h"

MCL_INLINE float node_entry(MCL_GLOBAL const BvhNode* n, float3 org, float3 invDir, float tmax) {
  return ray_box(org, invDir, make_float3(n->minX, n->minY, n->minZ),
                 make_float3(n->maxX, n->maxY, n->maxZ), tmax);
}

// Closest hit along org + t*dir for t in (0, tmax).
MCL_INLINE Hit bvh_closest_hit(MCL_GLOBAL const BvhNode* nodes, MCL_GLOBAL const Triangle* tris,
                               float3 org, float3 dir, float tmax) {
  Hit hit;
  hit.t = tmax;
  hit.tri = MCL_NO_HIT;
  hit.u = 0.0f;
  hit.v = 0.0f;
  float3 invDir = safe_inverse(dir);
  uint stack[MCL_BVH_STACK_SIZE];
  uint sp = 0;
  uint node = 0;
  if (node_entry(&nodes[0], org, invDir, hit.t) == INFINITY) {
    hit.t = INFINITY;  // a miss reads t = INFINITY whichever way it is found
    return hit;
  }
  for (;;) {
    MCL_GLOBAL const BvhNode* n = &nodes[node];
    if (n->triCount > 0) {
      for (uint i = 0; i < n->triCount; ++i) {
        uint ti = n->leftFirst + i;
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
      if (sp == 0) break;
      node = stack[--sp];
      continue;
    }
    // Visit the nearer child first; push the farther one if the ray enters it.
    uint a = n->leftFirst, b = n->leftFirst + 1;
    float da = node_entry(&nodes[a], org, invDir, hit.t);
    float db = node_entry(&nodes[b], org, invDir, hit.t);
    if (da > db) {
      float tf = da; da = db; db = tf;
      uint ti = a; a = b; b = ti;
    }
    if (da == INFINITY) {
      if (sp == 0) break;
      node = stack[--sp];
      continue;
    }
    node = a;
    if (db != INFINITY && sp < MCL_BVH_STACK_SIZE) stack[sp++] = b;
  }
  if (hit.tri == MCL_NO_HIT) hit.t = INFINITY;
  return hit;
}

// 1 if any triangle intersects org + t*dir for t in (0, tmax), else 0. Stops at the first hit.
MCL_INLINE int bvh_any_hit(MCL_GLOBAL const BvhNode* nodes, MCL_GLOBAL const Triangle* tris,
                           float3 org, float3 dir, float tmax) {
  float3 invDir = safe_inverse(dir);
  uint stack[MCL_BVH_STACK_SIZE];
  uint sp = 0;
  uint node = 0;
  if (node_entry(&nodes[0], org, invDir, tmax) == INFINITY) return 0;
  for (;;) {
    MCL_GLOBAL const BvhNode* n = &nodes[node];
    if (n->triCount > 0) {
      for (uint i = 0; i < n->triCount; ++i) {
        uint ti = n->leftFirst + i;
        float u = 0.0f, v = 0.0f;
        if (ray_triangle(org, dir, xyz(tris[ti].v0), xyz(tris[ti].e1), xyz(tris[ti].e2), tmax, &u,
                         &v) < tmax)
          return 1;
      }
      if (sp == 0) return 0;
      node = stack[--sp];
      continue;
    }
    uint a = n->leftFirst, b = n->leftFirst + 1;
    float da = node_entry(&nodes[a], org, invDir, tmax);
    float db = node_entry(&nodes[b], org, invDir, tmax);
    if (da > db) {
      float tf = da; da = db; db = tf;
      uint ti = a; a = b; b = ti;
    }
    if (da == INFINITY) {
      if (sp == 0) return 0;
      node = stack[--sp];
      continue;
    }
    node = a;
    if (db != INFINITY && sp < MCL_BVH_STACK_SIZE) stack[sp++] = b;
  }
}
