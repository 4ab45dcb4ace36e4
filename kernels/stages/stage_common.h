// stage_common.h: what several stage bodies share: the pixel and sample of a wave item, and the
// geometry of a hit (facing normal, position, shading frame, light emitted toward a direction).
// Pure functions of their arguments; compiled by the kernels and by the host backend.
// A wave holds `waveCount` consecutive indices g = waveStart + i into the active-pixel list,
// sample-major: pixel = active[g % activeCount], sample = g / activeCount, so a pixel's samples
// are always accumulated in sample order whatever the wave size. Without adaptive sampling the list
// holds every pixel in order.
#pragma once
#include "../shared/camera.h"
#include "../shared/lights.h"
#include "../shared/rng.h"
#include "../shared/sampling.h"
#include "../shared/shading.h"
#include "../shared/stage_table.h"
#include "../shared/surface_texture.h"

// The pixel and the sample index of wave item i.
MCL_INLINE uint item_pixel(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                           ulong waveStart, uint i) {
  return active[(uint)((waveStart + i) % f->activeCount)];
}
MCL_INLINE uint item_sample(MCL_CONSTANT const FrameParams* f, ulong waveStart, uint i) {
  return (uint)((waveStart + i) / f->activeCount);
}

// Unit normal n flipped to face the incoming direction.
MCL_INLINE float3 orient_facing(float3 n, float3 incoming) { return dot(n, incoming) > 0.0f ? -n : n; }

// Geometric normal of a hit triangle, flipped to face the incoming direction; finite at any scale
// (triangle_unit_normal). The stages read it precomputed (normals[t], surface_frame).
MCL_INLINE float3 facing_normal(MCL_GLOBAL const Triangle* tri, float3 incoming) {
  return orient_facing(triangle_unit_normal(xyz(tri->e1), xyz(tri->e2)), incoming);
}

// Hit position from barycentrics (more accurate than org + t * dir).
MCL_INLINE float3 hit_position(MCL_GLOBAL const Triangle* tri, Hit h) {
  return xyz(tri->v0) + xyz(tri->e1) * h.u + xyz(tri->e2) * h.v;
}

// The shading frame of hit h on triangle tris[h.tri] for a ray moving along `incoming`: position,
// geometric normal facing the ray, shading normal (shared/shading.h: interpolated corner normals
// on the geometric normal's side, read from shading[h.tri] only when the triangle's flags say it
// has normals; else the geometric normal, smooth = 0). The geometric normal is normals[h.tri]
// (precomputed triangle_unit_normal). Every shade stage and record_aov use it.
MCL_INLINE SurfaceFrame surface_frame(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const float4* normals,
                                      MCL_GLOBAL const TriangleShading* shading, Hit h, float3 incoming) {
  MCL_GLOBAL const Triangle* tri = &tris[h.tri];
  SurfaceFrame s;
  s.p = hit_position(tri, h);
  s.ng = orient_facing(xyz(normals[h.tri]), incoming);
  s.ns = s.ng;
  s.smooth = 0;
  if (as_uint(tri->e2.w) & MCL_ATTR_NORMALS) {
    MCL_GLOBAL const TriangleShading* a = &shading[h.tri];
    float3 n = interpolate_normal(xyz(a->n0), xyz(a->n1), xyz(a->n2), h.u, h.v);
    if (dot(n, n) > 0.0f) {
      s.ns = orient_to(n, s.ng);
      s.smooth = 1;
    }
  }
  return s;
}

// Le leaving a triangle of unit normal n and material m toward the viewer moving along dir (0 from
// the back face): emitters emit Ke from their front face (the side of cross(e1, e2)), or from both
// faces when emission.w is set.
MCL_INLINE float3 emitted_toward(float3 n, MCL_GLOBAL const Material* m, float3 dir) {
  float4 e = m->emission;
  bool front = dot(n, dir) < 0.0f;
  return front || e.w != 0.0f ? xyz(e) : make_float3(0.0f, 0.0f, 0.0f);
}

// Cosine at an emitter of unit normal n and material m for a direction wi from the shading point
// toward it: positive when wi reaches the emitting side (either side for a two-sided emitter).
MCL_INLINE float emitter_cosine(float3 n, MCL_GLOBAL const Material* m, float3 wi) {
  float c = -dot(n, wi);
  return m->emission.w != 0.0f ? fabs(c) : c;
}

// Pushes an occlusion query onto the shadow queue: if nothing blocks the ray from origin along unit
// dir before tmax, contribution c goes to shadowContrib[slot] (intersect_shadow). Every shade stage
// queries visibility through this one function.
MCL_INLINE void push_shadow_query(MCL_GLOBAL ShadowWork* queue, MCL_GLOBAL volatile uint* queueCount, float3 origin,
                                  float3 dir, float tmax, float3 c, uint slot) {
  ShadowWork w;
  w.ray.origin = with_w(origin, 0.0f);
  w.ray.dir = with_w(dir, tmax);
  w.r = c.x;
  w.g = c.y;
  w.b = c.z;
  w.slot = slot;
  queue[MCL_ATOMIC_INC(queueCount)] = w;
}

// The start of every shade stage: clears item i's shadow slots (a strategy leaves the slots it does
// not use at 0) and, when the camera ray missed, writes the background to radiance[i] and returns
// 0; otherwise returns 1 and leaves radiance[i] to the caller.
MCL_INLINE int shade_begin(MCL_CONSTANT const FrameParams* f, Hit h, uint i, MCL_GLOBAL float4* radiance,
                           MCL_GLOBAL float4* shadowContrib) {
  for (uint k = 0; k < f->shadowSlots; ++k)
    shadowContrib[i * f->shadowSlots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  if (h.tri != MCL_NO_HIT) return 1;
  radiance[i] = f->background;
  return 0;
}
