// direct_light.h: one light sample for next-event estimation, shared by the shade stages: the
// environment with probability env_pick_probability (shared/environment.h), else an emitter
// triangle by power and a uniform point on it; and the pdf with which light sampling would have
// produced a direction that BSDF sampling found (for MIS). Reads the emitter table, triangles,
// their precomputed normals and areas (normals), materials and the environment's tables; writes nothing.
#pragma once
#include "../shared/surface_bsdf.h"
#include "../shared/surface_texture.h"
#include "../shared/environment.h"
#include "stage_common.h"

typedef struct {
  float3 wi;    // unit direction from the shading point toward the light
  float3 le;    // radiance arriving along -wi if unoccluded
  float pdf;    // solid angle, light selection included; 0: no sample
  float tmax;   // shadow ray length (INFINITY for the environment)
} LightSample;

MCL_INLINE LightSample sample_direct_light(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const Triangle* tris,
                                           MCL_GLOBAL const float4* normals, MCL_GLOBAL const Material* materials,
                                           MCL_GLOBAL const Emitter* emitters,
                                           MCL_GLOBAL const float4* envMap, MCL_GLOBAL const float* envCdf,
                                           float3 origin, float4 u) {
  LightSample s;
  s.pdf = 0.0f;
  s.tmax = INFINITY;
  s.wi = make_float3(0.0f, 0.0f, 1.0f);
  s.le = make_float3(0.0f, 0.0f, 0.0f);
  float pEnv = env_pick_probability(f);
  if (u.x < pEnv) {  // never without an environment (pEnv = 0)
    EnvSample es = env_sample(f, envMap, envCdf, u.y, u.z);
    s.wi = es.wi;
    s.le = es.le;
    s.pdf = pEnv * es.pdf;
    return s;
  }
  float ux = pEnv > 0.0f ? (u.x - pEnv) / (1.0f - pEnv) : u.x;
  MCL_GLOBAL const Emitter* em = &emitters[pick_emitter(emitters, f->emitterCount, ux)];
  MCL_GLOBAL const Triangle* lt = &tris[em->tri];
  MCL_GLOBAL const Material* lm = &materials[triangle_material(lt)];
  float3 le = xyz(lm->emission);
  float3 p = sample_triangle(xyz(lt->v0), xyz(lt->e1), xyz(lt->e2), u.y, u.z);
  float3 toLight = p - origin;
  float dist2 = dot(toLight, toLight);
  float dist = sqrt(dist2);
  float3 wi = toLight / dist;
  float cosLight = emitter_cosine(xyz(normals[em->tri]), lm, wi);
  if (!(cosLight > 0.0f && dist > 0.0f)) return s;
  float pick = emitter_pick_probability(em->area, le, f->emitterPower);
  s.pdf = area_to_solid_angle(pick / em->area, dist2, cosLight);
  if (pEnv > 0.0f) s.pdf *= 1.0f - pEnv;
  s.wi = wi;
  s.le = le;
  s.tmax = dist * (1.0f - 1e-4f);
  return s;
}

// Light-sampling pdf of reaching emitter triangle lt (unit normal and area nA = normals[lt's
// index]) along wi at distance t (0 without emitters).
MCL_INLINE float emitter_light_pdf(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const Triangle* lt, float4 nA,
                                   MCL_GLOBAL const Material* materials, float3 wi, float t) {
  if (f->emitterCount == 0u) return 0.0f;
  MCL_GLOBAL const Material* lm = &materials[triangle_material(lt)];
  float area = nA.w;
  float cosLight = emitter_cosine(xyz(nA), lm, wi);
  float pick = emitter_pick_probability(area, xyz(lm->emission), f->emitterPower);
  float pdf = area_to_solid_angle(pick / area, t * t, cosLight);
  float pEnv = env_pick_probability(f);
  if (pEnv > 0.0f) pdf *= 1.0f - pEnv;
  return pdf;
}

// Light-sampling pdf of the environment along wi (0 without an environment).
MCL_INLINE float env_light_pdf(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* envMap, float3 wi) {
  float pEnv = env_pick_probability(f);
  return pEnv > 0.0f ? pEnv * env_pdf(f, envMap, wi) : 0.0f;
}
