// instance_space.h: a hit inside an instance, found in its object space, brought to world space:
// positions by the instance's object-to-world map, normals by the inverse transpose (the rows of
// world-to-object, transposed). Reads one Instance; pure (kernels and host tests).
//
// A surface frame computed in object space (with the object-space ray direction as `incoming`)
// maps to the world frame directly: dot(W^T n, d_world) = dot(n, W d_world) = dot(n, d_object), so
// the facing, the shading normal's side and the back-face flag are the same in both spaces. A
// mirroring instance needs no special case: its world normal W^T n is the normal of the mirrored
// surface, the one a flattened copy gets when the loader swaps its winding.
#pragma once
#include "shading.h"
#include "traverse_instances.h"

MCL_INLINE float3 instance_point(MCL_GLOBAL const Instance* in, float3 p) { return affine_point(in->objectToWorld, p); }

// Unit world-space normal of object-space normal n (n need not be unit).
MCL_INLINE float3 instance_normal(MCL_GLOBAL const Instance* in, float3 n) {
  MCL_GLOBAL const float4* w = in->worldToObject;
  return instance_normal_of(w[0], w[1], w[2], n);
}

// The world frame of an object-space frame s (computed for the object-space ray direction).
MCL_INLINE SurfaceFrame instance_frame(MCL_GLOBAL const Instance* in, SurfaceFrame s) {
  s.p = instance_point(in, s.p);
  s.ng = instance_normal(in, s.ng);
  s.ns = instance_normal(in, s.ns);  // ns == ng gives the same bits
  return s;
}
