// traverse.h: the BVH traversal the kernels run, picked when the program is built: the 8-wide BVH
// (traverse_wide.h, Bvh::wideNodes(); for CPUs) by default, the binary one (traverse_binary.h,
// Bvh::nodes; for GPUs) when the host passes -DMCL_BVH_BINARY (--bvh-layout, host/bvh/bvh_layout.h).
// BvhTraversalNode is what the kernels' nodes buffer holds. Both layouts find the same hits; the
// host reference calls either layout's functions by name. A two-level BVH (instances,
// traverse_instances.h) exists in the wide layout only: the binary program's bvh_instances_*
// find nothing (the host never runs it on instances).
#pragma once
#include "traverse_binary.h"
#include "traverse_instances.h"
#include "traverse_wide.h"

#ifdef MCL_BVH_BINARY
typedef BvhNode BvhTraversalNode;
MCL_INLINE Hit bvh_closest_hit(MCL_GLOBAL const BvhTraversalNode* nodes,
                               MCL_GLOBAL const Triangle* tris, const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  return binary_closest_hit(nodes, tris, alpha, org, dir, tmax);
}
MCL_INLINE int bvh_any_hit(MCL_GLOBAL const BvhTraversalNode* nodes,
                           MCL_GLOBAL const Triangle* tris, const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  return binary_any_hit(nodes, tris, alpha, org, dir, tmax);
}
MCL_INLINE InstanceHit bvh_instances_closest_hit(MCL_GLOBAL const BvhTraversalNode* nodes, MCL_GLOBAL const Triangle* tris,
                                                 MCL_GLOBAL const Instance* inst, const AlphaScene* alpha, float3 org,
                                                 float3 dir, float tmax) {
  (void)nodes, (void)tris, (void)inst, (void)alpha, (void)org, (void)dir, (void)tmax;
  InstanceHit r;
  r.hit.t = INFINITY;
  r.hit.tri = MCL_NO_HIT;
  r.hit.u = 0.0f;
  r.hit.v = 0.0f;
  r.instance = MCL_NO_INSTANCE;
  return r;
}
MCL_INLINE int bvh_instances_any_hit(MCL_GLOBAL const BvhTraversalNode* nodes, MCL_GLOBAL const Triangle* tris,
                                     MCL_GLOBAL const Instance* inst, const AlphaScene* alpha, float3 org, float3 dir,
                                     float tmax) {
  (void)nodes, (void)tris, (void)inst, (void)alpha, (void)org, (void)dir, (void)tmax;
  return 0;
}
#else
typedef WideNode BvhTraversalNode;
MCL_INLINE Hit bvh_closest_hit(MCL_GLOBAL const BvhTraversalNode* nodes,
                               MCL_GLOBAL const Triangle* tris, const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  return wide_closest_hit(nodes, tris, alpha, org, dir, tmax);
}
MCL_INLINE int bvh_any_hit(MCL_GLOBAL const BvhTraversalNode* nodes,
                           MCL_GLOBAL const Triangle* tris, const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  return wide_any_hit(nodes, tris, alpha, org, dir, tmax);
}
MCL_INLINE InstanceHit bvh_instances_closest_hit(MCL_GLOBAL const BvhTraversalNode* nodes, MCL_GLOBAL const Triangle* tris,
                                                 MCL_GLOBAL const Instance* inst, const AlphaScene* alpha, float3 org,
                                                 float3 dir, float tmax) {
  return instances_closest_hit(nodes, tris, inst, alpha, org, dir, tmax);
}
MCL_INLINE int bvh_instances_any_hit(MCL_GLOBAL const BvhTraversalNode* nodes, MCL_GLOBAL const Triangle* tris,
                                     MCL_GLOBAL const Instance* inst, const AlphaScene* alpha, float3 org, float3 dir,
                                     float tmax) {
  return instances_any_hit(nodes, tris, inst, alpha, org, dir, tmax);
}
#endif
