// bsdf_thin_dielectric.h: the material kind "thin_dielectric" (material_kinds.h): a thin sheet of
// index ior (a window pane) with two delta lobes: the mirror reflection with the sheet's
// reflectance R' = R + T^2 R / (1 - R^2) (R the single interface's Fresnel reflectance, T = 1 - R,
// the series of internal bounces summed; Mitsuba's thindielectric) and straight-through
// transmission (wi = -wo) with 1 - R'. Both sides alike. Reads a Material's params0.x (ior);
// pure; compiled by the kernels and the host tests. Written with selects (no early returns).
#pragma once
#include "bsdf_common.h"

typedef struct {
  float ior;
} ThinDielectricBsdf;

MCL_INLINE ThinDielectricBsdf thin_dielectric_from_material(Material m, float3 albedo) {
  (void)albedo;
  ThinDielectricBsdf b;
  b.ior = m.params0.x;
  return b;
}

MCL_INLINE int thin_dielectric_is_delta(ThinDielectricBsdf b) {
  (void)b;
  return 1;
}
MCL_INLINE float3 thin_dielectric_albedo(ThinDielectricBsdf b) {
  (void)b;
  return make_float3(1.0f, 1.0f, 1.0f);
}

MCL_INLINE float3 thin_dielectric_f(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return make_float3(0.0f, 0.0f, 0.0f);
}
MCL_INLINE float3 thin_dielectric_eval(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return make_float3(0.0f, 0.0f, 0.0f);
}
MCL_INLINE float thin_dielectric_pdf(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return 0.0f;
}

// The sheet's reflectance at cos_o = cosI.
MCL_INLINE float thin_dielectric_reflectance(ThinDielectricBsdf b, float cosI) {
  float cosT;
  float R = fresnel_dielectric(cosI, b.ior, &cosT);
  float T = 1.0f - R;
  return R < 1.0f ? R + T * T * R / (1.0f - R * R) : 1.0f;
}

MCL_INLINE BsdfSample thin_dielectric_sample(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                             float uLobe) {
  (void)u1; (void)u2;
  float cosI = dot(wo, s.ns);
  float R = thin_dielectric_reflectance(b, fmin(fmax(cosI, 0.0f), 1.0f));
  int refl = uLobe < R;
  BsdfSample r;
  r.wi = refl ? s.ns * (2.0f * cosI) - wo : -wo;
  int ok = cosI > 0.0f && (refl ? above_surface(s.ng, r.wi) : 1);
  r.pdf = ok ? (refl ? R : 1.0f - R) : 0.0f;
  r.weight = ok ? make_float3(1.0f, 1.0f, 1.0f) : make_float3(0.0f, 0.0f, 0.0f);
  r.flags = refl ? MCL_BSDF_DELTA : (MCL_BSDF_DELTA | MCL_BSDF_TRANSMISSION);
  return r;
}

MCL_INLINE BsdfDirection thin_dielectric_sample_direction(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float u1,
                                                          float u2, float uLobe) {
  return bsdf_direction_of(thin_dielectric_sample(b, s, wo, u1, u2, uLobe));
}

// Both lobes weigh 1 (each is picked with its own reflectance or transmittance).
MCL_INLINE BsdfWeight thin_dielectric_direction_weight(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi,
                                                       float pdf) {
  (void)b; (void)s; (void)wi; (void)wo;
  (void)pdf;
  BsdfWeight r;
  r.counts = 1;
  r.weight = make_float3(1.0f, 1.0f, 1.0f);
  return r;
}
