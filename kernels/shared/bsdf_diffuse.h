// bsdf_diffuse.h: the material kind "diffuse" (material_kinds.h): a Lambertian lobe (Kd, times the
// albedo texture) plus an optional GGX glossy lobe (Ks, roughness alpha; shared/microfacet.h).
// Reads a Material's albedo and specular fields; pure; compiled by the kernels and the host tests.
// Two layers:
// - around a unit normal n that faces wo (diffuse_*_about): the lobe is picked with probability
//   proportional to its luminance (Kd vs Ks); the pdf is the mixture of both lobes' pdfs (one-sample
//   MIS over lobes). With Ks = 0 every function reduces to the Lambertian expressions, operation for
//   operation (Lambert-only images are bit-identical to the renderer before the glossy lobe).
//   Kd + Ks <= 1 is ensured at load (energy conservation).
// - around a shading frame (the kind's interface, dispatched by shared/bsdf.h): without shading
//   normals (s.smooth == 0) each function is the one about the geometric normal, operation for
//   operation. With them: the lobes are built around ns; a direction below the geometric surface
//   contributes nothing (f = 0, pdf = 0: no light leaks); the Lambertian lobe's samples that fall
//   below the geometric surface are folded above it (shading.h, pdf_cosine_folded), while a glossy
//   sample below it is absorbed (the glossy pdf is its plain density above the surface, so the
//   mixture pdf stays exact).
#pragma once
#include "bsdf_common.h"
#include "microfacet.h"

#define MCL_DEFINE_DIFFUSE_TYPE(B, F, F3)                                                  \
  typedef struct {                                                                         \
    F3 kd;      /* Lambertian reflectance (Kd x albedo texture at the hit) */              \
    F3 ks;      /* glossy reflectance */                                                   \
    F alpha;    /* GGX roughness */                                                        \
    F specProb; /* probability of sampling the glossy lobe; 0 = Lambertian only */         \
  } B;
MCL_DEFINE_DIFFUSE_TYPE(DiffuseBsdf, float, float3)

MCL_INLINE DiffuseBsdf diffuse_make(float3 kd, float3 ks, float alpha) {
  DiffuseBsdf b;
  b.kd = kd;
  b.ks = ks;
  b.alpha = fmax(alpha, MCL_GGX_MIN_ALPHA);
  float ls = luminance(ks), ld = luminance(kd);
  b.specProb = ls > 0.0f ? ls / (ls + ld) : 0.0f;
  return b;
}

// A device material's lobes at a hit whose textured albedo is `albedo`. The lobe probability
// comes from the material's own Kd, not the texture's (as it always has: a textured surface
// samples its lobes the same everywhere).
MCL_INLINE DiffuseBsdf diffuse_from_material(Material m, float3 albedo) {
  DiffuseBsdf b = diffuse_make(xyz(m.albedo), xyz(m.specular), m.specular.w);
  b.kd = albedo;
  return b;
}

// No delta lobe (the glossy lobe's alpha is at least MCL_GGX_MIN_ALPHA).
MCL_INLINE int diffuse_is_delta(DiffuseBsdf b) {
  (void)b;
  return 0;
}


// --- the glossy mixture (specProb > 0), written once for floats and lanes ----------------------
// P, F, F3, M, V, ANY: the prefix, float, float3, int mask, f3 and MCL_ANY1 here; the packet
// stages' v_, vfloat, vfloat3, vmask, v3, v_any in stages/lane_bsdf.h, with their frame FR and
// sample type BS. Selects, not branches: a lane performs the scalar function's operations in order.
// - glossy_*_about: about a unit normal n facing wo: f (no cosine) and f cos, 0 when wi or wo is
//   below the surface; the mixture pdf; a sample from u1, u2 (the lobe's warp) and uLobe (the pick).
// - glossy_f, _eval, _pdf, _sample: around a shading frame: about ng where flat; where smooth about ns,
//   nothing below the geometric surface, the cosine lobe's samples folded above it (its pdf the
//   folded one) and a glossy sample below it absorbed.
#define MCL_DEFINE_DIFFUSE_GLOSSY(P, F, F3, M, V, ANY, B, FR, BS)                                            \
  MCL_INLINE F3 P##glossy_f_about(B b, F3 n, F3 wo, F3 wi) {                                                \
    F cosI = V##_dot(n, wi);                                                                                \
    M ok = (cosI > 0.0f) & (V##_dot(n, wo) > 0.0f);                                                         \
    F g = P##ggx_eval_cos(P##to_local(wo, n), P##to_local(wi, n), b.alpha) / cosI;                          \
    return V##_select(ok, V##_add(V##_scale(b.kd, MCL_INV_PI), V##_scale(b.ks, g)),                         \
                      V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                           \
  }                                                                                                         \
  MCL_INLINE F3 P##glossy_eval_about(B b, F3 n, F3 wo, F3 wi) {                                             \
    return V##_scale(P##glossy_f_about(b, n, wo, wi), fmax(V##_dot(n, wi), 0.0f));                          \
  }                                                                                                         \
  MCL_INLINE F P##glossy_pdf_about(B b, F3 n, F3 wo, F3 wi) {                                               \
    F cosI = V##_dot(n, wi);                                                                                \
    M ok = (cosI > 0.0f) & (V##_dot(n, wo) > 0.0f);                                                         \
    F p = (1.0f - b.specProb) * P##pdf_cosine_hemisphere(cosI) +                                            \
          b.specProb * P##ggx_pdf(P##to_local(wo, n), P##to_local(wi, n), b.alpha);                         \
    return vsel(ok, p, (F)(0.0f));                                                                          \
  }                                                                                                         \
  MCL_INLINE BS P##glossy_sample_about(B b, F3 n, F3 wo, F u1, F u2, F uLobe) {                             \
    F3 woL = P##to_local(wo, n);                                                                            \
    F3 wiL = V##_select(uLobe < b.specProb,                                                                 \
                        P##reflect_about(woL, P##ggx_sample_visible_normal(woL, b.alpha, u1, u2)),          \
                        P##sample_cosine_hemisphere(u1, u2));                                               \
    BS r;                                                                                                   \
    r.wi = P##to_world(wiL, n);                                                                             \
    F pdf = (1.0f - b.specProb) * P##pdf_cosine_hemisphere(wiL.z) + b.specProb * P##ggx_pdf(woL, wiL, b.alpha); \
    F3 fcos = V##_add(V##_scale(b.kd, MCL_INV_PI * wiL.z), V##_scale(b.ks, P##ggx_eval_cos(woL, wiL, b.alpha))); \
    M ok = (woL.z > 0.0f) & (wiL.z > 0.0f) & (pdf > 0.0f);                                                  \
    r.pdf = vsel(ok, pdf, (F)(0.0f));                                                                       \
    r.weight = V##_select(ok, V##_scale(fcos, 1.0f / pdf), V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));      \
    r.flags = (M)(0);                                                                                       \
    return r;                                                                                               \
  }                                                                                                         \
  MCL_INLINE F3 P##glossy_eval(B b, FR s, F3 wo, F3 wi) {                                                   \
    F3 e = P##glossy_eval_about(b, V##_select(s.smooth, s.ns, s.ng), wo, wi);                               \
    M below = s.smooth & ((V##_dot(s.ng, wi) > 0.0f) == (M)(0));                                            \
    return V##_select(below, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)), e);                                 \
  }                                                                                                         \
  MCL_INLINE F3 P##glossy_f(B b, FR s, F3 wo, F3 wi) {                                                      \
    F3 e = P##glossy_f_about(b, V##_select(s.smooth, s.ns, s.ng), wo, wi);                                  \
    M below = s.smooth & ((V##_dot(s.ng, wi) > 0.0f) == (M)(0));                                            \
    return V##_select(below, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)), e);                                 \
  }                                                                                                         \
  MCL_INLINE F P##glossy_pdf(B b, FR s, F3 wo, F3 wi) {                                                     \
    F p = (F)(0.0f);                                                                                        \
    if (ANY(s.smooth)) {                                                                                    \
      F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                          \
      F spec = vsel((woL.z > 0.0f) & (wiL.z > 0.0f), P##ggx_pdf(woL, wiL, b.alpha), (F)(0.0f));             \
      F mix = (1.0f - b.specProb) * P##pdf_cosine_folded(s.ns, s.ng, wi) + b.specProb * spec;               \
      p = vsel(V##_dot(s.ng, wi) > 0.0f, mix, (F)(0.0f));                                                   \
    }                                                                                                       \
    if (ANY(s.smooth == (M)(0))) p = vsel(s.smooth, p, P##glossy_pdf_about(b, s.ng, wo, wi));               \
    return p;                                                                                               \
  }                                                                                                         \
  MCL_INLINE BS P##glossy_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                                   \
    BS r;                                                                                                   \
    r.wi = s.ns;                                                                                            \
    r.weight = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                                   \
    r.pdf = (F)(0.0f);                                                                                      \
    r.flags = (M)(0);                                                                                       \
    if (ANY(s.smooth)) {                                                                                    \
      M glossy = uLobe < b.specProb;                                                                        \
      F3 woL = P##to_local(wo, s.ns);                                                                       \
      F3 wg = P##to_world(P##reflect_about(woL, P##ggx_sample_visible_normal(woL, b.alpha, u1, u2)), s.ns); \
      F3 wd = P##fold_above(P##to_world(P##sample_cosine_hemisphere(u1, u2), s.ns), s.ng);                  \
      r.wi = V##_select(glossy, wg, wd);                                                                    \
      F pdf = P##glossy_pdf(b, s, wo, r.wi);                                                                \
      M ok = ((glossy == (M)(0)) | (woL.z > 0.0f)) & (pdf > 0.0f);                                          \
      r.pdf = vsel(ok, pdf, (F)(0.0f));                                                                     \
      r.weight = V##_select(ok, V##_scale(P##glossy_eval(b, s, wo, r.wi), 1.0f / pdf), r.weight);          \
    }                                                                                                       \
    if (ANY(s.smooth == (M)(0))) {                                                                          \
      BS f = P##glossy_sample_about(b, s.ng, wo, u1, u2, uLobe);                                            \
      r.wi = V##_select(s.smooth, r.wi, f.wi);                                                              \
      r.weight = V##_select(s.smooth, r.weight, f.weight);                                                  \
      r.pdf = vsel(s.smooth, r.pdf, f.pdf);                                                                 \
    }                                                                                                       \
    return r;                                                                                               \
  }
MCL_DEFINE_DIFFUSE_GLOSSY(, float, float3, int, f3, MCL_ANY1, DiffuseBsdf, SurfaceFrame, BsdfSample)

// --- about a unit normal n facing wo (the Lambertian lobe, or the glossy mixture above) --------

// f (no cosine); 0 when wi or wo is below the surface.
MCL_INLINE float3 diffuse_f_about(DiffuseBsdf b, float3 n, float3 wo, float3 wi) {
  float cosI = dot(n, wi);
  if (b.specProb == 0.0f) return cosI > 0.0f ? b.kd * MCL_INV_PI : make_float3(0.0f, 0.0f, 0.0f);
  return glossy_f_about(b, n, wo, wi);
}

// f * cos(n, wi).
MCL_INLINE float3 diffuse_eval_about(DiffuseBsdf b, float3 n, float3 wo, float3 wi) {
  float c = dot(n, wi);
  if (b.specProb == 0.0f) return c > 0.0f ? b.kd * (c * MCL_INV_PI) : make_float3(0.0f, 0.0f, 0.0f);
  return glossy_eval_about(b, n, wo, wi);
}

// Solid-angle pdf of diffuse_sample_about producing wi.
MCL_INLINE float diffuse_pdf_about(DiffuseBsdf b, float3 n, float3 wo, float3 wi) {
  if (b.specProb == 0.0f) return pdf_cosine_hemisphere(dot(n, wi));
  return glossy_pdf_about(b, n, wo, wi);
}

// wi, weight = f cos / pdf, pdf (0: no sample) from u1, u2 (the lobe's warp) and uLobe (the pick).
MCL_INLINE BsdfSample diffuse_sample_about(DiffuseBsdf b, float3 n, float3 wo, float u1, float u2, float uLobe) {
  if (b.specProb != 0.0f) return glossy_sample_about(b, n, wo, u1, u2, uLobe);
  BsdfSample s;  // Lambertian: f cos / p = Kd exactly
  float3 dirLocal = sample_cosine_hemisphere(u1, u2);  // sampling.h: same bits on every device
  s.wi = to_world(dirLocal, n);
  s.pdf = pdf_cosine_hemisphere(dirLocal.z);
  s.weight = s.pdf > 0.0f ? b.kd : make_float3(0.0f, 0.0f, 0.0f);
  s.flags = 0;
  return s;
}

// --- the kind's interface: around a shading frame ---------------------------------------------

// f (no cosine) for wo, wi.
MCL_INLINE float3 diffuse_f(DiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  if (!s.smooth) return diffuse_f_about(b, s.ng, wo, wi);
  if (!above_surface(s.ng, wi)) return make_float3(0.0f, 0.0f, 0.0f);
  return diffuse_f_about(b, s.ns, wo, wi);
}

// f * cos(ns, wi), zero below the geometric surface.
MCL_INLINE float3 diffuse_eval(DiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  if (!s.smooth) return diffuse_eval_about(b, s.ng, wo, wi);
  if (!above_surface(s.ng, wi)) return make_float3(0.0f, 0.0f, 0.0f);
  return diffuse_eval_about(b, s.ns, wo, wi);
}

// Solid-angle pdf of diffuse_sample producing wi.
MCL_INLINE float diffuse_pdf(DiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  if (b.specProb != 0.0f) return glossy_pdf(b, s, wo, wi);
  if (!s.smooth) return diffuse_pdf_about(b, s.ng, wo, wi);
  return above_surface(s.ng, wi) ? pdf_cosine_folded(s.ns, s.ng, wi) : 0.0f;
}

// A direction from the BSDF: wi, weight = f cos / pdf, pdf (0: absorbed).
MCL_INLINE BsdfSample diffuse_sample(DiffuseBsdf b, SurfaceFrame s, float3 wo, float u1, float u2, float uLobe) {
  if (b.specProb != 0.0f) return glossy_sample(b, s, wo, u1, u2, uLobe);
  if (!s.smooth) return diffuse_sample_about(b, s.ng, wo, u1, u2, uLobe);
  BsdfSample r;
  r.weight = make_float3(0.0f, 0.0f, 0.0f);
  r.pdf = 0.0f;
  r.flags = 0;
  r.wi = frame_sample_direction(s, sample_cosine_hemisphere(u1, u2));
  float pdf = diffuse_pdf(b, s, wo, r.wi);
  if (!(pdf > 0.0f)) return r;
  r.pdf = pdf;
  r.weight = diffuse_eval(b, s, wo, r.wi) * (1.0f / pdf);
  return r;
}

// The albedo AOV and the direct integrator's weight, written once for floats and lanes (lane_bsdf.h):
// - diffuse_albedo: Kd x texture (the glossy lobe is left out, as denoisers expect);
// - diffuse_direction_weight: f cos / p of a direction wi that shade_direct drew (the cosine lobe,
//   or the glossy mixture's sample) whose pdf (diffuse_pdf) is pdf; *counts: whether it
//   contributes (bsdf_common.h). Lambert-only: Kd times cosine_weight (shading.h); the glossy
//   mixture: glossy_eval / pdf.
#define MCL_DEFINE_DIFFUSE_WEIGHTS(P, F, F3, M, V, ANY, B, FR)                                          \
  MCL_INLINE F3 P##diffuse_albedo(B b) { return b.kd; }                                                 \
  MCL_INLINE F3 P##diffuse_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {                \
    M lambert = b.specProb == 0.0f;                                                                     \
    *counts = lambert | (pdf > 0.0f);                                                                   \
    F3 w = V##_scale(b.kd, P##cosine_weight(s.ns, s.ng, s.smooth, wi));                                 \
    if (ANY(lambert == (M)(0))) w = V##_select(lambert, w, V##_scale(P##glossy_eval(b, s, wo, wi), 1.0f / pdf)); \
    return w;                                                                                           \
  }
MCL_DEFINE_DIFFUSE_WEIGHTS(, float, float3, int, f3, MCL_ANY1, DiffuseBsdf, SurfaceFrame)
