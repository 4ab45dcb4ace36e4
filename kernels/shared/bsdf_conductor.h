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
#pragma once
#include "bsdf_common.h"
#include "microfacet.h"
#include "microfacet_beckmann.h"

// The kind's parameters and its eval, pdf and sample, written once for floats and lanes (P, F, F3,
// M, V, ANY: the prefix, float, float3, int mask, f3, MCL_ANY1 here; the packet stages' v_,
// vfloat, vfloat3, vmask, v3, v_any in stages/lane_bsdf.h, with their frame FR and sample type
// BS): selects, not branches, so a lane performs the scalar function's operations in the same order.
#define MCL_DEFINE_CONDUCTOR_TYPE(B, F, F3, M)                                                   \
  typedef struct {                                                                               \
    F3 eta, k;                                                                                   \
    F3 factor;  /* multiplies the Fresnel term */                                                \
    F alpha;    /* 0: smooth (delta); else the microfacets' roughness, at least MCL_GGX_MIN_ALPHA */ \
    M smooth;   /* alpha == 0 */                                                                 \
    M beckmann; /* rough: Beckmann microfacets, else GGX */                                      \
  } B;
MCL_DEFINE_CONDUCTOR_TYPE(ConductorBsdf, float, float3, int)

// conductor_make: from eta, k and alpha (factor 1, GGX). conductor_fresnel: F(cos) x the factor.
// conductor_eval: f * cos(ns, wi) of the rough lobe; 0 for a smooth conductor (delta) and below
// either surface; conductor_f: f (eval over the cosine). conductor_pdf: its pdf. conductor_sample: smooth: the mirror direction about ns
// with weight F(cos_o), pdf 1 (the only lobe), flag delta; rough: a visible normal, wi its
// reflection, weight eval / pdf.
#define MCL_DEFINE_CONDUCTOR(P, F, F3, M, V, ANY, B, FR, BS)                                      \
  MCL_INLINE B P##conductor_make(F3 eta, F3 k, F alpha) {                                        \
    B b;                                                                                         \
    b.eta = eta;                                                                                 \
    b.k = k;                                                                                     \
    b.factor = V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f));                                        \
    b.smooth = (alpha > 0.0f) == (M)(0);                                                         \
    b.alpha = fmax(alpha, MCL_GGX_MIN_ALPHA);                                                    \
    b.beckmann = (M)(0);                                                                         \
    return b;                                                                                    \
  }                                                                                              \
  MCL_INLINE F3 P##conductor_fresnel(B b, F cosI) {                                              \
    return V##_mul(P##fresnel_conductor(cosI, b.eta, b.k), b.factor);                            \
  }                                                                                              \
  MCL_INLINE F3 P##conductor_eval(B b, FR s, F3 wo, F3 wi) {                                     \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                 \
    M ok = (b.smooth == (M)(0)) & (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);  \
    F3 h = V##_normalize(V##_add(woL, wiL));                                                     \
    F3 fr = P##conductor_fresnel(b, fmin(fmax(V##_dot(woL, h), 0.0f), 1.0f));                    \
    F g = P##ggx_eval_cos(woL, wiL, b.alpha);                                                    \
    if (ANY(b.beckmann)) g = vsel(b.beckmann, P##beckmann_eval_cos(woL, wiL, b.alpha), g);       \
    g = vsel(ok, g, (F)(0.0f));                                                                  \
    return V##_select(ok, V##_scale(fr, g), V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));          \
  }                                                                                              \
  MCL_INLINE F3 P##conductor_f(B b, FR s, F3 wo, F3 wi) {                                        \
    return P##over_cosine(P##conductor_eval(b, s, wo, wi), V##_dot(s.ns, wi));                   \
  }                                                                                              \
  MCL_INLINE F P##conductor_pdf(B b, FR s, F3 wo, F3 wi) {                                       \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                 \
    M ok = (b.smooth == (M)(0)) & (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);  \
    return vsel(ok, P##ggx_pdf(woL, wiL, b.alpha), (F)(0.0f));                                   \
  }                                                                                              \
  MCL_INLINE BS P##conductor_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                     \
    (void)uLobe;                                                                                 \
    F3 woL = P##to_local(wo, s.ns);                                                              \
    M up = woL.z > 0.0f;                                                                         \
    M rough = (b.smooth == (M)(0)) & up;                                                         \
    F3 hL = V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f));                                           \
    if (ANY(rough)) hL = V##_select(rough, P##ggx_sample_visible_normal(woL, b.alpha, u1, u2), hL); \
    F3 wiL = P##reflect_about(woL, hL);                                                          \
    BS r;                                                                                        \
    r.wi = P##to_world(wiL, s.ns);                                                               \
    M ok = up & (wiL.z > 0.0f) & (V##_dot(s.ng, r.wi) > 0.0f);                                   \
    F pdf = (F)(1.0f);                                                                           \
    F3 w = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                            \
    if (ANY(b.smooth)) w = P##conductor_fresnel(b, fmin(woL.z, 1.0f));                          \
    if (ANY(b.smooth == (M)(0))) { /* the rough lobe: weight eval / pdf */                       \
      F pr = P##conductor_pdf(b, s, wo, r.wi);                                                   \
      pdf = vsel(b.smooth, pdf, pr);                                                             \
      w = V##_select(b.smooth, w, V##_scale(P##conductor_eval(b, s, wo, r.wi), 1.0f / fmax(pr, 1e-30f))); \
    }                                                                                            \
    ok = ok & (pdf > 0.0f);                                                                      \
    r.pdf = vsel(ok, pdf, (F)(0.0f));                                                            \
    r.weight = V##_select(ok, w, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                     \
    r.flags = vsel(b.smooth, (M)(MCL_BSDF_DELTA), (M)(0));                                       \
    return r;                                                                                    \
  }
MCL_DEFINE_CONDUCTOR(, float, float3, int, f3, MCL_ANY1, ConductorBsdf, SurfaceFrame, BsdfSample)

MCL_INLINE ConductorBsdf conductor_from_material(Material m, float3 albedo) {
  (void)albedo;
  ConductorBsdf b = conductor_make(xyz(m.params0), xyz(m.params1), m.params0.w);
  b.factor = xyz(m.specular);
  b.beckmann = m.params1.w > 0.5f;
  return b;
}

MCL_INLINE int conductor_is_delta(ConductorBsdf b) { return b.smooth; }


// Written once for floats and lanes (lane_bsdf.h):
// - conductor_albedo: the albedo AOV, the reflectance at normal incidence, F(1) (an approximation
//   of the directional albedo that ignores the Fresnel rise at grazing angles and the rough lobe's
//   energy loss);
// - conductor_direction_weight: pdf is conductor_pdf of wi (0 for the smooth kind, whose weight is
//   rebuilt from wo: F(cos_o), counted above the geometric surface).
#define MCL_DEFINE_CONDUCTOR_WEIGHTS(P, F, F3, M, V, B, FR)                                             \
  MCL_INLINE F3 P##conductor_albedo(B b) { return P##conductor_fresnel(b, (F)(1.0f)); }                 \
  MCL_INLINE F3 P##conductor_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {              \
    F cosO = fmin(fmax(V##_dot(wo, s.ns), 0.0f), 1.0f);                                                 \
    *counts = vsel(b.smooth, V##_dot(s.ng, wi) > 0.0f, pdf > 0.0f);                                     \
    F3 rough = V##_scale(P##conductor_eval(b, s, wo, wi), 1.0f / fmax(pdf, 1e-30f));                    \
    return V##_select(b.smooth, P##conductor_fresnel(b, cosO), rough);                                  \
  }
MCL_DEFINE_CONDUCTOR_WEIGHTS(, float, float3, int, f3, ConductorBsdf, SurfaceFrame)
