// bsdf_dielectric.h: the material kind "dielectric" (material_kinds.h): an interface between
// the outside (index 1, the triangle's front face: the side of cross(v1 - v0, v2 - v0)) and the
// inside (index ior). Reads a Material's params0 (x: ior, y: alpha, z: tinted by the albedo,
// transmission_tint.h); the side from SurfaceFrame::backface. Pure; compiled by the kernels and
// the host tests. Written with selects (no early returns).
// alpha 0 (smooth): one delta reflection and one delta refraction lobe, picked with the Fresnel
// reflectance F (bsdf_common.h fresnel_dielectric) as probability, so both weights are exact:
// reflection 1, refraction 1 / eta^2 (radiance transport: radiance is scaled by (n_i / n_t)^2
// across the interface, as Mitsuba's dielectric and pbrt's DielectricBxDF do), and by the tint
// (white but for glTF's glass: its base colour; both lobes below). Around the shading
// normal ns: a reflection below the geometric surface, or a refraction above it, is absorbed.
// alpha > 0 (rough): GGX microfacet reflection and transmission (Walter et al. 2007, "Microfacet
// Models for Refraction through Rough Surfaces"; Mitsuba's roughdielectric with distribution ggx,
// sample_visible): a visible normal h (microfacet.h), then reflection about h with probability
// F(wo.h), else refraction through h; the separable Smith G = G1(wo) G1(wi); the refracted lobe
// scaled by 1 / eta^2 as the smooth one. Not delta: eval and pdf are densities for directions on
// both sides (a reflection must leave above the geometric surface, a transmission below it).
#pragma once
#include "bsdf_common.h"
#include "microfacet.h"
#include "transmission_tint.h"

#define MCL_DEFINE_DIELECTRIC_TYPE(B, F, F3, M)                                       \
  typedef struct {                                                                    \
    F ior;    /* inside / outside */                                                  \
    F alpha;  /* GGX roughness of the rough kind, at least MCL_GGX_MIN_ALPHA */       \
    M smooth; /* alpha == 0: the delta lobes */                                       \
    F3 tint;  /* on the transmitted light (transmission_tint.h); white: clear glass */ \
  } B;
MCL_DEFINE_DIELECTRIC_TYPE(DielectricBsdf, float, float3, int)

// The kind's make, eta, lobes and sample, written once for floats and lanes (P, F, F3, M, V, ANY:
// the prefix, float, float3, int mask, f3, MCL_ANY1 here; the packet stages' v_, vfloat, vfloat3,
// vmask, v3, v_any in stages/lane_bsdf.h, with their frame FR and sample type BS): selects, not
// branches, so a lane performs the scalar function's operations in the same order.
// - dielectric_eta: eta = n_transmitted / n_incident for a ray arriving on the side s.backface says.
// - rough_dielectric_eval_local: the rough lobes at local wo (above: wo.z > 0, the side of index
//   n_i), wi, for eta = n_t / n_i: f * |cos_i| (returned) and the solid-angle pdf of the rough
//   sample (*pdf). The half vector is the generalised one, h ~ wo + eta' wi (eta' = 1 for a
//   reflection, eta for a transmission), turned to +z; wo must see h (wo.h > 0) and wi lie on the
//   side of h its lobe leaves by. With D = D(h), G = G1(wo) G1(wi), F = F(wo.h), c = wi.h + wo.h / eta:
//     reflection:   f cos = F D G / (4 wo.z),                pdf = F G1(wo) D / (4 wo.z)
//     transmission: f cos = (1 - F) D G |wi.h| wo.h / (wo.z c^2 eta^2),
//                   pdf = (1 - F) G1(wo) D wo.h / wo.z * |wi.h| / c^2
//   (pdf: the visible-normal density D_wo(h) = G1(wo) D wo.h / wo.z times the lobe's probability
//   and the Jacobian dh / dwi, 1 / (4 wo.h) and |wi.h| / c^2). So f cos / pdf = G1(wi), and
//   G1(wi) / eta^2 for a transmission. side: the geometric side test of wi (0: nothing).
// - dielectric_eval_pdf: f * |cos(ns, wi)| of the rough lobes around ns (a transmission's times
//   the tint) and their pdf (*pdf); 0 for
//   the smooth kind (delta lobes only) and for a reflection below the geometric surface or a
//   transmission above it; dielectric_f: f = eval / |cos(ns, wi)| (a transmitted wi has a negative
//   cosine).
// - dielectric_sample_rough: a visible normal h for wo, then uLobe < F(wo.h) reflects wo about h,
//   else wo refracts through h (flag transmission); weight eval / pdf (G1(wi), over eta^2 for a
//   transmission), pdf dielectric_pdf's. A direction on the wrong geometric side is absorbed.
// - dielectric_sample_smooth: uLobe < F: the mirror direction (weight 1, pdf F); else the refracted
//   one (weight 1 / eta^2, pdf 1 - F, flag transmission). Both flagged delta.
#define MCL_DEFINE_DIELECTRIC(P, F, F3, M, V, ANY, B, FR, BS)                                                    \
  MCL_INLINE B P##dielectric_make(F ior, F alpha) {                                                        \
    B b;                                                                                                   \
    b.ior = ior;                                                                                           \
    b.smooth = (alpha > 0.0f) == (M)(0);                                                                   \
    b.alpha = fmax(alpha, MCL_GGX_MIN_ALPHA);                                                              \
    b.tint = V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f));                                                    \
    return b;                                                                                              \
  }                                                                                                        \
  MCL_INLINE F P##dielectric_eta(B b, FR s) { return vsel(s.backface, 1.0f / b.ior, b.ior); }             \
  MCL_INLINE F P##rough_dielectric_eval_local(F3 wo, F3 wi, F eta, F alpha, M side, F* pdf) {              \
    M refl = wi.z > 0.0f;                                                                                  \
    F etaP = vsel(refl, (F)(1.0f), eta);                                                                   \
    F3 hr = V##_add(wo, V##_scale(wi, etaP));                                                              \
    F len2 = V##_dot(hr, hr);                                                                              \
    F3 h = V##_scale(hr, 1.0f / sqrt(fmax(len2, 1e-30f)));                                                 \
    h = V##_select(h.z < 0.0f, V##_neg(h), h);                                                             \
    F dO = V##_dot(wo, h), dI = V##_dot(wi, h);                                                            \
    M ok = side & (wo.z > 0.0f) & (wi.z != 0.0f) & (len2 > 1e-30f) & (dO > 0.0f) &                         \
           vsel(refl, dI > 0.0f, dI < 0.0f);                                                               \
    F cosT;                                                                                                \
    F fr = P##fresnel_dielectric(fmin(fmax(dO, 0.0f), 1.0f), eta, &cosT);                                  \
    F d = P##ggx_d(h, alpha);                                                                              \
    F g1o = P##ggx_g1(wo, alpha);                                                                          \
    F g1i = P##ggx_g1(wi, alpha);                                                                          \
    F c = dI + dO / eta;                                                                                   \
    F c2 = fmax(c * c, 1e-30f);                                                                            \
    F cosO = fmax(wo.z, 1e-30f);                                                                           \
    F pr = fr * g1o * d / (4.0f * cosO);                                                                   \
    F pt = (1.0f - fr) * g1o * d * dO / cosO * (fabs(dI) / c2);                                            \
    F p = vsel(refl, pr, pt);                                                                              \
    F w = vsel(refl, g1i, g1i / (eta * eta));                                                              \
    *pdf = vsel(ok, p, (F)(0.0f));                                                                         \
    return vsel(ok, p * w, (F)(0.0f));                                                                     \
  }                                                                                                        \
  MCL_INLINE F3 P##dielectric_eval_pdf(B b, FR s, F3 wo, F3 wi, F* pdf) {                                  \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                           \
    M side = vsel(wiL.z > 0.0f, V##_dot(s.ng, wi) > 0.0f, V##_dot(s.ng, wi) < 0.0f);                       \
    F e = P##rough_dielectric_eval_local(woL, wiL, P##dielectric_eta(b, s), b.alpha,                       \
                                         side & (b.smooth == (M)(0)), pdf);                                \
    return P##tint_transmitted(b.tint, (wiL.z > 0.0f) == (M)(0), e);                                      \
  }                                                                                                        \
  MCL_INLINE F3 P##dielectric_f(B b, FR s, F3 wo, F3 wi) {                                                 \
    F p;                                                                                                   \
    return P##over_cosine(P##dielectric_eval_pdf(b, s, wo, wi, &p), fabs(V##_dot(s.ns, wi)));              \
  }                                                                                                        \
  MCL_INLINE BS P##dielectric_sample_rough(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                        \
    F eta = P##dielectric_eta(b, s);                                                                       \
    F3 woL = P##to_local(wo, s.ns);                                                                        \
    M up = woL.z > 0.0f;                                                                                   \
    F3 hL = P##ggx_sample_visible_normal(V##_select(up, woL, V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f))),   \
                                         b.alpha, u1, u2);                                                 \
    F cosI = V##_dot(woL, hL);                                                                             \
    F cosT;                                                                                                \
    F fr = P##fresnel_dielectric(fmin(fmax(cosI, 0.0f), 1.0f), eta, &cosT);                                \
    M refl = uLobe < fr;                                                                                   \
    F3 wr = P##reflect_about(woL, hL);                                                                     \
    F3 wt = V##_sub(V##_scale(hL, cosI / eta - cosT), V##_scale(woL, 1.0f / eta));                         \
    F3 wiL = V##_select(refl, wr, V##_normalize(wt));                                                      \
    BS r;                                                                                                  \
    r.wi = P##to_world(wiL, s.ns);                                                                         \
    F pdf;                                                                                                 \
    F3 fcos = P##dielectric_eval_pdf(b, s, wo, r.wi, &pdf);                                                \
    /* The lobe drawn must be the lobe evaluated (a refraction that rounding put above ns is lost). */     \
    M ok = up & (pdf > 0.0f) & vsel(refl, wiL.z > 0.0f, wiL.z < 0.0f);                                     \
    F3 w = V##_scale(fcos, 1.0f / fmax(pdf, 1e-30f));                                                      \
    r.pdf = vsel(ok, pdf, (F)(0.0f));                                                                      \
    r.weight = V##_select(ok, w, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                               \
    r.flags = vsel(refl, (M)(0), (M)(MCL_BSDF_TRANSMISSION));                                              \
    return r;                                                                                              \
  }                                                                                                        \
  MCL_INLINE BS P##dielectric_sample_smooth(B b, FR s, F3 wo, F uLobe) {                                   \
    F eta = P##dielectric_eta(b, s);                                                                       \
    F cosI = V##_dot(wo, s.ns);                                                                            \
    F cosT;                                                                                                \
    F fr = P##fresnel_dielectric(fmin(fmax(cosI, 0.0f), 1.0f), eta, &cosT);                                \
    M refl = uLobe < fr;                                                                                   \
    F3 wr = V##_sub(V##_scale(s.ns, 2.0f * cosI), wo);                                                     \
    F3 wt = V##_sub(V##_scale(s.ns, cosI / eta - cosT), V##_scale(wo, 1.0f / eta));                        \
    BS r;                                                                                                  \
    r.wi = V##_select(refl, wr, V##_normalize(wt));                                                        \
    F dg = V##_dot(s.ng, r.wi);                                                                            \
    M ok = (cosI > 0.0f) & vsel(refl, dg > 0.0f, dg < 0.0f);                                               \
    F w = vsel(refl, (F)(1.0f), 1.0f / (eta * eta));                                                       \
    r.pdf = vsel(ok, vsel(refl, fr, 1.0f - fr), (F)(0.0f));                                                \
    r.weight = V##_select(ok, P##tint_transmitted(b.tint, refl == (M)(0), w),                              \
                          V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                      \
    r.flags = vsel(refl, (M)(MCL_BSDF_DELTA), (M)(MCL_BSDF_DELTA | MCL_BSDF_TRANSMISSION));                \
    return r;                                                                                              \
  }                                                                                                        \
  MCL_INLINE BS P##dielectric_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                              \
    M rough = b.smooth == (M)(0);                                                                          \
    BS r;                                                                                                  \
    if (ANY(b.smooth)) r = P##dielectric_sample_smooth(b, s, wo, uLobe);                                   \
    else r = P##dielectric_sample_rough(b, s, wo, u1, u2, uLobe);                                          \
    if (ANY(b.smooth) && ANY(rough)) { /* both kinds in the packet: the rough lanes' own */                \
      BS q = P##dielectric_sample_rough(b, s, wo, u1, u2, uLobe);                                          \
      r.wi = V##_select(rough, q.wi, r.wi);                                                                \
      r.weight = V##_select(rough, q.weight, r.weight);                                                    \
      r.pdf = vsel(rough, q.pdf, r.pdf);                                                                   \
      r.flags = vsel(rough, q.flags, r.flags);                                                             \
    }                                                                                                      \
    return r;                                                                                              \
  }
MCL_DEFINE_DIELECTRIC(, float, float3, int, f3, MCL_ANY1, DielectricBsdf, SurfaceFrame, BsdfSample)

MCL_INLINE DielectricBsdf dielectric_from_material(Material m, float3 albedo) {
  DielectricBsdf b = dielectric_make(m.params0.x, m.params0.y);
  b.tint = transmission_tint_of(m.params0.z, albedo);
  return b;
}

MCL_INLINE int dielectric_is_delta(DielectricBsdf b) { return b.smooth; }
MCL_INLINE float3 dielectric_eval(DielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float p;
  return dielectric_eval_pdf(b, s, wo, wi, &p);
}
MCL_INLINE float dielectric_pdf(DielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float p;
  (void)dielectric_eval_pdf(b, s, wo, wi, &p);
  return p;
}
// Written once for floats and lanes (lane_bsdf.h):
// - dielectric_albedo: the albedo AOV (the tint not counted): the directional albedo at normal
//   incidence from outside, counted in energy (reflected plus transmitted, without the 1 / eta^2
//   of radiance), as the conductor's F(1): 1 for the smooth kind (clear glass reflects and
//   transmits everything); the rough kind keeps E = the mean over wo's visible normals h of
//   F G1(reflected) + (1 - F) G1(refracted) (what dielectric_sample's weights average to, times
//   eta^2 for a transmission; single-scattering GGX loses the rest). At normal incidence the
//   visible normals are symmetric about wo, so E is a 1-D integral over u1 (the disk radius^2 of
//   ggx_sample_visible_normal): 32 midpoints of u1 = 1 - (1 - x)^2, weight 2 (1 - x), crowded
//   toward the grazing microfacets where the integrand bends (within 1e-4 of the integral for
//   alpha in [0.01, 1], ior 1.5 and 2.4; an 8 x 8 grid in (u1, u2) was 6e-3 off;
//   tests/test_bsdf_rough_dielectric.cpp).
// - dielectric_direction_weight: the weight of a direction dielectric_sample drew. Smooth: rebuilt
//   from its side: above the geometric surface the reflection (1), below it the refraction
//   (1 / eta^2, times the tint). Rough: eval / pdf (pdf: dielectric_pdf of wi).
#define MCL_DEFINE_DIELECTRIC_WEIGHTS(P, F, F3, M, V, B, FR)                                                    \
  MCL_INLINE F3 P##dielectric_albedo(B b) {                                                                     \
    F3 wo = V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f));                                                          \
    F eta = b.ior;                                                                                              \
    F sum = (F)(0.0f);                                                                                          \
    for (int i = 0; i < 32; ++i) {                                                                              \
      float x = ((float)i + 0.5f) * (1.0f / 32.0f);                                                             \
      F3 h = P##ggx_sample_visible_normal(wo, b.alpha, (F)(1.0f - (1.0f - x) * (1.0f - x)), (F)(0.0f));         \
      F cosI = fmin(fmax(h.z, 0.0f), 1.0f);                                                                     \
      F cosT;                                                                                                   \
      F fr = P##fresnel_dielectric(cosI, eta, &cosT);                                                           \
      F3 wr = P##reflect_about(wo, h);                                                                          \
      F3 wt = V##_normalize(V##_sub(V##_scale(h, cosI / eta - cosT), V##_scale(wo, 1.0f / eta)));               \
      F gr = vsel(wr.z > 0.0f, P##ggx_g1(wr, b.alpha), (F)(0.0f));                                              \
      F gt = vsel(wt.z < 0.0f, P##ggx_g1(wt, b.alpha), (F)(0.0f));                                              \
      sum += (fr * gr + (1.0f - fr) * gt) * (2.0f * (1.0f - x));                                                \
    }                                                                                                           \
    F e = vsel(b.smooth, (F)(1.0f), sum * (1.0f / 32.0f));                                                      \
    return V##_make(e, e, e);                                                                                   \
  }                                                                                                             \
  MCL_INLINE F3 P##dielectric_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {                     \
    F eta = P##dielectric_eta(b, s);                                                                            \
    M above = V##_dot(s.ng, wi) > 0.0f;                                                                         \
    F w = vsel(above, (F)(1.0f), 1.0f / (eta * eta));                                                           \
    F p;                                                                                                        \
    F3 wr = V##_scale(P##dielectric_eval_pdf(b, s, wo, wi, &p), 1.0f / fmax(pdf, 1e-30f));                      \
    *counts = b.smooth | (pdf > 0.0f);                                                                          \
    return V##_select(b.smooth, P##tint_transmitted(b.tint, above == (M)(0), w), wr);                           \
  }
MCL_DEFINE_DIELECTRIC_WEIGHTS(, float, float3, int, f3, DielectricBsdf, SurfaceFrame)
