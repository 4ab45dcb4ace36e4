// light_scene.h: what the light kinds (light_<kind>.h) read, bundled: LightScene (the emitter
// table, triangles, their normals, materials, the environment's tables), LightSample (a light
// sample for next-event estimation) and LightHit (where a BSDF ray found a light). Pure types;
// compiled by the kernels and by the host.
#pragma once
#include "texture.h"

typedef struct {
  MCL_GLOBAL const Triangle* tris;      // BVH order
  MCL_GLOBAL const float4* normals;     // per triangle: unit geometric normal (xyz), area (w)
  MCL_GLOBAL const Material* materials;
  MCL_GLOBAL const Emitter* emitters;   // may be null where nothing samples (shade_direct_hit)
  MCL_GLOBAL const float4* envMap;
  MCL_GLOBAL const float* envCdf;       // may be null where nothing samples
  MCL_GLOBAL const LightRecord* records;  // point, spot, directional, sun; may be null where nothing samples
  MCL_GLOBAL const TriangleShading* shading;  // per triangle (BVH order): UVs of textured emitters
  TextureTables tex;                          // emission textures
} LightScene;

MCL_INLINE LightScene make_light_scene(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const float4* normals,
                                       MCL_GLOBAL const Material* materials, MCL_GLOBAL const Emitter* emitters,
                                       MCL_GLOBAL const float4* envMap, MCL_GLOBAL const float* envCdf,
                                       MCL_GLOBAL const LightRecord* records, MCL_GLOBAL const TriangleShading* shading,
                                       TextureTables tex) {
  LightScene s;
  s.tris = tris;
  s.normals = normals;
  s.materials = materials;
  s.emitters = emitters;
  s.envMap = envMap;
  s.envCdf = envCdf;
  s.records = records;
  s.shading = shading;
  s.tex = tex;
  return s;
}

typedef struct {
  float3 wi;    // unit direction from the shading point toward the light
  float3 le;    // radiance arriving along -wi if unoccluded
  float pdf;    // solid angle, light selection included; 0: no sample
  float tmax;   // shadow ray length (INFINITY for the environment)
  int delta;    // 1: a delta light (point, spot, directional): pdf is the discrete probability of
                // picking it, no BSDF ray can reach it, so the sample takes no MIS weight
} LightSample;

// The light a ray from a shading point along wi reached: a triangle tri at distance t (kind area;
// it may emit nothing), or nothing (kind environment). Delta lights are never hit.
typedef struct {
  uint kind;  // MCL_LIGHT_<kind>
  uint tri;
  float t;
  float u, v;  // barycentrics of the hit on tri (where an emission texture is read)
  float3 wi;
} LightHit;

MCL_INLINE LightSample no_light_sample(void) {
  LightSample s;
  s.pdf = 0.0f;
  s.tmax = INFINITY;
  s.wi = make_float3(0.0f, 0.0f, 1.0f);
  s.le = make_float3(0.0f, 0.0f, 0.0f);
  s.delta = 0;
  return s;
}
