// light_area.h: the light kind "area" (light_kinds.h): emitting triangles. Reads the emitter table
// (Emitter: picked with probability area * emitter_luminance / emitterPower: luminance(Ke), or a
// textured emitter's mean over the triangle), the triangles, their normals and areas, their
// materials' emission and emission textures (with the triangles' UVs); pure; compiled by the
// kernels and the host. Emitters emit Le = Ke (x the emission texture at the point) from their
// front face (the side of cross(e1, e2)), or from both faces when the material's emission.w is set;
// a light sample on a stochastically transparent one is weighted by its coverage.
#pragma once
#include "environment.h"
#include "light_scene.h"
#include "lights.h"
#include "surface_texture.h"

// Le = le leaving a triangle of unit normal n and material m toward the viewer moving along dir
// (0 from the back face).
MCL_INLINE float3 emitted_toward(float3 n, MCL_GLOBAL const Material* m, float3 le, float3 dir) {
  bool front = dot(n, dir) < 0.0f;
  return front || m->emission.w != 0.0f ? le : make_float3(0.0f, 0.0f, 0.0f);
}

// Cosine at an emitter of unit normal n and material m for a direction wi from the shading point
// toward it: positive when wi reaches the emitting side (either side for a two-sided emitter).
MCL_INLINE float emitter_cosine(float3 n, MCL_GLOBAL const Material* m, float3 wi) {
  float c = -dot(n, wi);
  return m->emission.w != 0.0f ? fabs(c) : c;
}

// The emitters' share of the lights' power (all samples without other lights).
MCL_INLINE float area_light_probability(MCL_CONSTANT const FrameParams* f) {
  return f->emitterCount > 0u ? f->shareArea : 0.0f;
}

// An emitter by power (u0), a uniform point on it (u1, u2); pdf per solid angle within the kind.
MCL_INLINE LightSample area_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float u0,
                                         float u1, float u2) {
  LightSample s = no_light_sample();
  MCL_GLOBAL const Emitter* em = &ls.emitters[pick_emitter(ls.emitters, f->emitterCount, u0)];
  MCL_GLOBAL const Triangle* lt = &ls.tris[em->tri];
  MCL_GLOBAL const Material* lm = &ls.materials[triangle_material(lt)];
  float3 p = sample_triangle(xyz(lt->v0), xyz(lt->e1), xyz(lt->e2), u1, u2);
  float su = sqrt(u1);  // the barycentrics of p (sample_triangle's), for the emission texture
  float3 le = material_emission(ls.tex, lm, lt, &ls.shading[em->tri], su * (1.0f - u2), su * u2);
  // A stochastically transparent emitter (BLEND) sends its emission times its coverage there: the
  // expectation of a ray that meets it with that probability (written once with the lanes':
  // surface_texture.h's coverage_of).
  if (material_blends(lm)) le = le * material_coverage(ls.tex, lm, lt, &ls.shading[em->tri], su * (1.0f - u2), su * u2);
  float3 toLight = p - origin;
  float dist2 = dot(toLight, toLight);
  float dist = sqrt(dist2);
  float3 wi = toLight / dist;
  float cosLight = emitter_cosine(xyz(ls.normals[em->tri]), lm, wi);
  if (!(cosLight > 0.0f && dist > 0.0f)) return s;
  float pick = em->area * emitter_luminance(ls.tex, lm, lt, &ls.shading[em->tri]) / f->emitterPower;
  s.pdf = area_to_solid_angle(pick / em->area, dist2, cosLight);
  s.wi = wi;
  s.le = le;
  s.tmax = dist * (1.0f - 1e-4f);
  return s;
}

// Pdf within the kind of reaching triangle hit.tri along hit.wi at distance hit.t (0 without
// emitters).
MCL_INLINE float area_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  if (f->emitterCount == 0u) return 0.0f;
  MCL_GLOBAL const Triangle* lt = &ls.tris[hit.tri];
  MCL_GLOBAL const Material* lm = &ls.materials[triangle_material(lt)];
  float4 nA = ls.normals[hit.tri];
  float area = nA.w;
  float cosLight = emitter_cosine(xyz(nA), lm, hit.wi);
  float pick = area * emitter_luminance(ls.tex, lm, lt, &ls.shading[hit.tri]) / f->emitterPower;
  return area_to_solid_angle(pick / area, hit.t * hit.t, cosLight);
}

// Le the triangle hit.tri sends back along -hit.wi (0 for a non-emitter or its back face).
MCL_INLINE float3 area_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  MCL_GLOBAL const Triangle* lt = &ls.tris[hit.tri];
  MCL_GLOBAL const Material* lm = &ls.materials[triangle_material(lt)];
  float3 le = material_emission(ls.tex, lm, lt, &ls.shading[hit.tri], hit.u, hit.v);
  return emitted_toward(xyz(ls.normals[hit.tri]), lm, le, hit.wi);
}
