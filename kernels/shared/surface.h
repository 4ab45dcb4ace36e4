// surface.h: what a shade stage knows about the surface at a hit, from one call: surface_at reads
// the hit triangle, its precomputed normal, its attributes (TriangleShading), its material and
// the textures, and returns the shading frame and the BSDF (kind, parameters, textured albedo).
// Pure; compiled by the kernels, the host backend and the host tests.
#pragma once
#include "bsdf.h"
#include "lights.h"
#include "shading.h"
#include "bump_map.h"
#include "instance_space.h"
#include "normal_map.h"
#include "surface_texture.h"
#include "transmission_mix.h"

// What surface_at reads: the scene's triangles (BVH order), their unit geometric normals and
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

// surface_frame for a hit in instance inst (MCL_NO_INSTANCE: a world-space triangle, today's
// frame): computed in the instance's object space with the object-space direction, then placed
// (instance_space.h; the facing and back-face flag agree in both spaces).
MCL_INLINE SurfaceFrame surface_frame_in(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const float4* normals,
                                         MCL_GLOBAL const TriangleShading* shading,
                                         MCL_GLOBAL const Instance* instances, Hit h, uint inst, float3 incoming) {
  if (inst == MCL_NO_INSTANCE) return surface_frame(tris, normals, shading, h, incoming);
  MCL_GLOBAL const Instance* in = &instances[inst];
  return instance_frame(in, surface_frame(tris, normals, shading, h, affine_vector(in->worldToObject, incoming)));
}

typedef struct {
  SurfaceFrame frame;
  Bsdf bsdf;
} Surface;

// The surface at hit h (h.tri != MCL_NO_HIT) of a ray moving along unit direction dir, whose
// length to the hit is h.t (the albedo texture's footprint is the camera's ray cone there), with
// the triangle and dir in one space (world, or an instance's object space: surface_at below), for
// sample r (which kind a partly transmissive material is at this hit, transmission_mix.h).
MCL_INLINE Surface surface_at_object(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, Hit h, float3 dir,
                                     SampleRef r) {
  MCL_GLOBAL const Triangle* tri = &sc.tris[h.tri];
  Material m = sc.materials[triangle_material(tri)];
  Surface s;
  s.frame = surface_frame(sc.tris, sc.normals, sc.shading, h, dir);
  s.frame = apply_normal_map(s.frame, sc.tex, m, tri, &sc.shading[h.tri], xyz(sc.normals[h.tri]), h);
  s.frame = apply_bump_map(s.frame, sc.tex, m, tri, &sc.shading[h.tri], xyz(sc.normals[h.tri]), h);
  float3 albedo = hit_albedo(sc.tex, f, m, tri, sc.normals[h.tri], &sc.shading[h.tri], h, dir);
  m = hit_metal_rough(sc.tex, f, m, tri, sc.normals[h.tri], &sc.shading[h.tri], h, dir);
  m = hit_transmission_texture(sc.tex, f, m, tri, sc.normals[h.tri], &sc.shading[h.tri], h, dir);
  m = hit_transmission(f, m, r, h, dir);
  s.bsdf = bsdf_from_material(m, albedo);
  return s;
}

// The surface at hit h in instance inst (MCL_NO_INSTANCE: a world-space triangle, surface_at_object
// as it always was), for sample r. In an instance everything is computed in its object space, with
// the unit object-space direction, then the frame is placed (instance_space.h); the albedo texture's
// footprint then uses the object-space area, so a scaled instance may pick another mip level
// than a flattened copy would. Every shade stage and record_aov read their surface through this
// one function.
MCL_INLINE Surface surface_at(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, Hit h, uint inst, float3 dir,
                              SampleRef r) {
  if (inst == MCL_NO_INSTANCE) return surface_at_object(sc, f, h, dir, r);
  MCL_GLOBAL const Instance* in = &sc.instances[inst];
  Surface s = surface_at_object(sc, f, h, normalize(affine_vector(in->worldToObject, dir)), r);
  s.frame = instance_frame(in, s.frame);
  return s;
}
