// surface.h: what the shade stages read about the surface at a hit (SurfaceScene: the hit triangle,
// its precomputed normal, its attributes (TriangleShading), its material, the textures and the
// instances; the stages build the frame and BSDF from it in lanes, lane_frame in
// stages/stage_lanes.h), and the flat frame of a hit (surface_frame) that the host's ray sets and
// tests use. Pure; compiled by the kernels, the host backend and the host tests.
#pragma once
#include "bsdf.h"
#include "lights.h"
#include "shading.h"
#include "bump_map.h"
#include "instance_space.h"
#include "normal_map.h"
#include "surface_texture.h"
#include "transmission_mix.h"

// What the shade stages read: the scene's triangles (BVH order), their unit geometric normals and
// areas (normals[t]: xyz, w), attributes, materials and texture tables; with a two-level BVH the
// triangles, normals and corner normals of instanced meshes are in their object space, and
// instances holds the placements (Instance).
typedef struct {
  MCL_GLOBAL const Triangle* tris;
  MCL_GLOBAL const float4* normals;
  MCL_GLOBAL const TriangleShading* shading;
  MCL_GLOBAL const Material* materials;
  TextureTables tex;
  MCL_GLOBAL const Instance* instances;
} SurfaceScene;

MCL_INLINE SurfaceScene make_surface_scene(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const float4* normals,
                                           MCL_GLOBAL const TriangleShading* shading,
                                           MCL_GLOBAL const Material* materials, TextureTables tt,
                                           MCL_GLOBAL const Instance* instances) {
  SurfaceScene s;
  s.tris = tris;
  s.normals = normals;
  s.shading = shading;
  s.materials = materials;
  s.tex = tt;
  s.instances = instances;
  return s;
}

// The SurfaceScene of a stage's arguments a (every shading stage's table row names these fields).
#define MCL_STAGE_SURFACE_SCENE(a)                                                                 \
  make_surface_scene((a)->tris, (a)->normals, (a)->shading, (a)->materials,                       \
                     make_surface_tables((a)->textures, (a)->textureLevels, (a)->texels, (a)->vertexColors,     \
                                         (a)->tangents),                                                   \
                     (a)->instances)

// Unit normal n flipped to face the incoming direction.
#define MCL_DEFINE_ORIENT_FACING(P, F3, V) \
  MCL_INLINE F3 P##orient_facing(F3 n, F3 incoming) { return V##_select(V##_dot(n, incoming) > 0.0f, V##_neg(n), n); }
MCL_DEFINE_ORIENT_FACING(, float3, f3)

// Hit position from barycentrics (more accurate than org + t * dir).
MCL_INLINE float3 hit_position(MCL_GLOBAL const Triangle* tri, Hit h) {
  return xyz(tri->v0) + xyz(tri->e1) * h.u + xyz(tri->e2) * h.v;
}

// The shading frame of hit h on triangle tris[h.tri] for a ray moving along `incoming`: position,
// geometric normal facing the ray, shading normal (shared/shading.h: interpolated corner normals
// on the geometric normal's side, read from shading[h.tri] only when the triangle's flags say it
// has normals; else the geometric normal, smooth = 0). The geometric normal is normals[h.tri]
// (precomputed triangle_unit_normal).
MCL_INLINE SurfaceFrame surface_frame(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const float4* normals,
                                      MCL_GLOBAL const TriangleShading* shading, Hit h, float3 incoming) {
  MCL_GLOBAL const Triangle* tri = &tris[h.tri];
  SurfaceFrame s;
  s.p = hit_position(tri, h);
  s.ng = orient_facing(xyz(normals[h.tri]), incoming);
  s.ns = s.ng;
  s.smooth = 0;
  s.backface = dot(xyz(normals[h.tri]), incoming) > 0.0f;
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
