// bsdf_conductor.h: the material kind "conductor" (material_kinds.h): a metal of complex index of
// refraction eta + i k (per RGB channel, relative to the outside), exact unpolarised Fresnel
// (bsdf_common.h fresnel_conductor) times a factor (Mitsuba's specular_reflectance, Tungsten's
// albedo; 1 for pbrt's conductor). alpha 0: a smooth mirror (one delta lobe); alpha > 0: a GGX
// microfacet lobe (shared/microfacet.h) sampled by visible normals, f = F(wo.h) D G2 / (4 cos_o
// cos_i) (Mitsuba's roughconductor, pbrt's ConductorBxDF), or a Beckmann one of the same alpha
// (microfacet_beckmann.h; sampled by the same GGX visible normals). Reads a Material's params0
// (xyz: eta, w: alpha), params1 (xyz: k, w: 1 for Beckmann, 0 for GGX) and specular (xyz: the
// factor); pure; compiled by the kernels and the host tests.
// Around the shading normal ns; a direction below the geometric surface contributes nothing.
// Written with selects (no early returns) so the kind can later run in lanes.
#pragma once
#include "bsdf_common.h"
#include "microfacet.h"
#include "microfacet_beckmann.h"

typedef struct {
  float3 eta, k;
  float3 factor;  // multiplies the Fresnel term
  float alpha;    // 0: smooth (delta); else the microfacets' roughness, at least MCL_GGX_MIN_ALPHA
  int smooth;     // alpha == 0
  int beckmann;   // rough: Beckmann microfacets, else GGX
} ConductorBsdf;

MCL_INLINE ConductorBsdf conductor_make(float3 eta, float3 k, float alpha) {
  ConductorBsdf b;
  b.eta = eta;
  b.k = k;
  b.factor = make_float3(1.0f, 1.0f, 1.0f);
  b.smooth = !(alpha > 0.0f);
  b.alpha = fmax(alpha, MCL_GGX_MIN_ALPHA);
  b.beckmann = 0;
  return b;
}

MCL_INLINE ConductorBsdf conductor_from_material(Material m, float3 albedo) {
  (void)albedo;
  ConductorBsdf b = conductor_make(xyz(m.params0), xyz(m.params1), m.params0.w);
  b.factor = xyz(m.specular);
  b.beckmann = m.params1.w > 0.5f;
  return b;
}

// F(cos) x the factor.
MCL_INLINE float3 conductor_fresnel(ConductorBsdf b, float cosI) { return fresnel_conductor(cosI, b.eta, b.k) * b.factor; }

MCL_INLINE int conductor_is_delta(ConductorBsdf b) { return b.smooth; }

// The albedo AOV: the reflectance at normal incidence, F(1) (an approximation of the directional
// albedo that ignores the Fresnel rise at grazing angles and the rough lobe's energy loss).
MCL_INLINE float3 conductor_albedo(ConductorBsdf b) { return conductor_fresnel(b, 1.0f); }

// f * cos(ns, wi) of the rough lobe; 0 for a smooth conductor (delta) and below either surface.
MCL_INLINE float3 conductor_eval(ConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  int ok = !b.smooth && above_surface(s.ng, wi) && woL.z > 0.0f && wiL.z > 0.0f;
  float3 h = normalize(woL + wiL);
  float3 fr = conductor_fresnel(b, fmin(fmax(dot(woL, h), 0.0f), 1.0f));
  float g = ok ? (b.beckmann ? beckmann_eval_cos(woL, wiL, b.alpha) : ggx_eval_cos(woL, wiL, b.alpha)) : 0.0f;
  return ok ? fr * g : make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float3 conductor_f(ConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float c = dot(s.ns, wi);
  return c > 0.0f ? conductor_eval(b, s, wo, wi) * (1.0f / c) : make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float conductor_pdf(ConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  int ok = !b.smooth && above_surface(s.ng, wi) && woL.z > 0.0f && wiL.z > 0.0f;
  return ok ? ggx_pdf(woL, wiL, b.alpha) : 0.0f;
}

// Smooth: the mirror direction about ns with weight F(cos_o), pdf 1 (the only lobe), flag delta.
// Rough: a visible normal, wi its reflection, weight eval / pdf.
MCL_INLINE BsdfSample conductor_sample(ConductorBsdf b, SurfaceFrame s, float3 wo, float u1, float u2, float uLobe) {
  (void)uLobe;
  float3 woL = to_local(wo, s.ns);
  int up = woL.z > 0.0f;
  float3 hL = b.smooth || !up ? make_float3(0.0f, 0.0f, 1.0f) : ggx_sample_visible_normal(woL, b.alpha, u1, u2);
  float3 wiL = reflect_about(woL, hL);
  BsdfSample r;
  r.wi = to_world(wiL, s.ns);
  int ok = up && wiL.z > 0.0f && above_surface(s.ng, r.wi);
  float pdf = b.smooth ? 1.0f : conductor_pdf(b, s, wo, r.wi);
  ok = ok && pdf > 0.0f;
  float3 w = b.smooth ? conductor_fresnel(b, fmin(woL.z, 1.0f))
                      : conductor_eval(b, s, wo, r.wi) * (1.0f / fmax(pdf, 1e-30f));
  r.pdf = ok ? pdf : 0.0f;
  r.weight = ok ? w : make_float3(0.0f, 0.0f, 0.0f);
  r.flags = b.smooth ? MCL_BSDF_DELTA : 0;
  return r;
}

MCL_INLINE BsdfDirection conductor_sample_direction(ConductorBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                                    float uLobe) {
  return bsdf_direction_of(conductor_sample(b, s, wo, u1, u2, uLobe));
}

// pdf: conductor_pdf of wi (0 for the smooth kind, whose weight is rebuilt from wo: F(cos_o)).
MCL_INLINE BsdfWeight conductor_direction_weight(ConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi, float pdf) {
  BsdfWeight w;
  float cosO = fmin(fmax(dot(wo, s.ns), 0.0f), 1.0f);
  w.counts = b.smooth ? above_surface(s.ng, wi) : pdf > 0.0f;
  w.weight = b.smooth ? conductor_fresnel(b, cosO)
                      : conductor_eval(b, s, wo, wi) * (1.0f / fmax(pdf, 1e-30f));
  return w;
}
