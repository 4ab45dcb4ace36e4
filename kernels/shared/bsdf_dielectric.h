// bsdf_dielectric.h: the material kind "dielectric" (material_kinds.h): a smooth interface between
// the outside (index 1, the triangle's front face: the side of cross(v1 - v0, v2 - v0)) and the
// inside (index ior), with one delta reflection and one delta refraction lobe, picked with the
// Fresnel reflectance F (bsdf_common.h fresnel_dielectric) as probability, so both weights are
// exact: reflection 1, refraction 1 / eta^2 (radiance transport: radiance is scaled by
// (n_i / n_t)^2 across the interface, as Mitsuba's dielectric and pbrt's DielectricBxDF do).
// Reads a Material's params0.x (ior); the side from SurfaceFrame::backface. Pure; compiled by the
// kernels and the host tests. Around the shading normal ns: a reflection below the geometric
// surface, or a refraction above it, is absorbed. Written with selects (no early returns).
#pragma once
#include "bsdf_common.h"

typedef struct {
  float ior;  // inside / outside
} DielectricBsdf;

MCL_INLINE DielectricBsdf dielectric_from_material(Material m, float3 albedo) {
  (void)albedo;
  DielectricBsdf b;
  b.ior = m.params0.x;
  return b;
}

MCL_INLINE int dielectric_is_delta(DielectricBsdf b) {
  (void)b;
  return 1;
}
// The albedo AOV: 1 (clear glass reflects and transmits everything).
MCL_INLINE float3 dielectric_albedo(DielectricBsdf b) {
  (void)b;
  return make_float3(1.0f, 1.0f, 1.0f);
}

// Delta lobes only: f, eval and pdf are 0 for every direction.
MCL_INLINE float3 dielectric_f(DielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return make_float3(0.0f, 0.0f, 0.0f);
}
MCL_INLINE float3 dielectric_eval(DielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return make_float3(0.0f, 0.0f, 0.0f);
}
MCL_INLINE float dielectric_pdf(DielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return 0.0f;
}

// eta = n_transmitted / n_incident for a ray arriving on the side s.backface says.
MCL_INLINE float dielectric_eta(DielectricBsdf b, SurfaceFrame s) { return s.backface ? 1.0f / b.ior : b.ior; }

// uLobe < F: the mirror direction (weight 1, pdf F); else the refracted one (weight 1 / eta^2,
// pdf 1 - F, flag transmission). Both flagged delta.
MCL_INLINE BsdfSample dielectric_sample(DielectricBsdf b, SurfaceFrame s, float3 wo, float u1, float u2, float uLobe) {
  (void)u1; (void)u2;
  float eta = dielectric_eta(b, s);
  float cosI = dot(wo, s.ns);
  float cosT;
  float F = fresnel_dielectric(fmin(fmax(cosI, 0.0f), 1.0f), eta, &cosT);
  int refl = uLobe < F;
  float3 wr = s.ns * (2.0f * cosI) - wo;
  float3 wt = s.ns * (cosI / eta - cosT) - wo * (1.0f / eta);
  BsdfSample r;
  r.wi = refl ? wr : normalize(wt);
  int ok = cosI > 0.0f && (refl ? above_surface(s.ng, r.wi) : dot(s.ng, r.wi) < 0.0f);
  float w = refl ? 1.0f : 1.0f / (eta * eta);
  r.pdf = ok ? (refl ? F : 1.0f - F) : 0.0f;
  r.weight = ok ? make_float3(w, w, w) : make_float3(0.0f, 0.0f, 0.0f);
  r.flags = refl ? MCL_BSDF_DELTA : (MCL_BSDF_DELTA | MCL_BSDF_TRANSMISSION);
  return r;
}

MCL_INLINE BsdfDirection dielectric_sample_direction(DielectricBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                                     float uLobe) {
  return bsdf_direction_of(dielectric_sample(b, s, wo, u1, u2, uLobe));
}

// The weight of a direction dielectric_sample drew, rebuilt from its side: above the geometric
// surface the reflection (1), below it the refraction (1 / eta^2).
MCL_INLINE BsdfWeight dielectric_direction_weight(DielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi, float pdf) {
  (void)pdf; (void)wo;
  float eta = dielectric_eta(b, s);
  float w = above_surface(s.ng, wi) ? 1.0f : 1.0f / (eta * eta);
  BsdfWeight r;
  r.counts = 1;
  r.weight = make_float3(w, w, w);
  return r;
}
