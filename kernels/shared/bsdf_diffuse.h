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

typedef struct {
  float3 kd;        // Lambertian reflectance (Kd x albedo texture at the hit)
  float3 ks;        // glossy reflectance
  float alpha;      // GGX roughness
  float specProb;   // probability of sampling the glossy lobe; 0 = Lambertian only
} DiffuseBsdf;

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

// What the albedo AOV shows: Kd x texture (the glossy lobe is left out, as denoisers expect).
MCL_INLINE float3 diffuse_albedo(DiffuseBsdf b) { return b.kd; }

// --- about a unit normal n facing wo ---------------------------------------------------------

// f (no cosine); 0 when wi or wo is below the surface.
MCL_INLINE float3 diffuse_f_about(DiffuseBsdf b, float3 n, float3 wo, float3 wi) {
  float cosI = dot(n, wi);
  if (b.specProb == 0.0f) return cosI > 0.0f ? b.kd * MCL_INV_PI : make_float3(0.0f, 0.0f, 0.0f);
  float cosO = dot(n, wo);
  if (!(cosI > 0.0f && cosO > 0.0f)) return make_float3(0.0f, 0.0f, 0.0f);
  float g = ggx_eval_cos(to_local(wo, n), to_local(wi, n), b.alpha) / cosI;
  return b.kd * MCL_INV_PI + b.ks * g;
}

// f * cos(n, wi).
MCL_INLINE float3 diffuse_eval_about(DiffuseBsdf b, float3 n, float3 wo, float3 wi) {
  float c = dot(n, wi);
  if (b.specProb == 0.0f) return c > 0.0f ? b.kd * (c * MCL_INV_PI) : make_float3(0.0f, 0.0f, 0.0f);
  return diffuse_f_about(b, n, wo, wi) * fmax(c, 0.0f);
}

// Solid-angle pdf of diffuse_sample_about producing wi.
MCL_INLINE float diffuse_pdf_about(DiffuseBsdf b, float3 n, float3 wo, float3 wi) {
  float cosI = dot(n, wi);
  if (b.specProb == 0.0f) return pdf_cosine_hemisphere(cosI);
  if (!(cosI > 0.0f && dot(n, wo) > 0.0f)) return 0.0f;
  return (1.0f - b.specProb) * pdf_cosine_hemisphere(cosI) +
         b.specProb * ggx_pdf(to_local(wo, n), to_local(wi, n), b.alpha);
}

// wi, weight = f cos / pdf, pdf (0: no sample) from u1, u2 (the lobe's warp) and uLobe (the pick).
MCL_INLINE BsdfSample diffuse_sample_about(DiffuseBsdf b, float3 n, float3 wo, float u1, float u2, float uLobe) {
  BsdfSample s;
  if (b.specProb == 0.0f) {  // Lambertian: f cos / p = Kd exactly
    float3 dirLocal = sample_cosine_hemisphere(u1, u2);  // sampling.h: same bits on every device
    s.wi = to_world(dirLocal, n);
    s.pdf = pdf_cosine_hemisphere(dirLocal.z);
    s.weight = s.pdf > 0.0f ? b.kd : make_float3(0.0f, 0.0f, 0.0f);
    s.flags = 0;
    return s;
  }
  float3 woL = to_local(wo, n);
  s.weight = make_float3(0.0f, 0.0f, 0.0f);
  s.pdf = 0.0f;
  s.flags = 0;
  s.wi = n;
  if (!(woL.z > 0.0f)) return s;
  float3 wiL;
  if (uLobe < b.specProb) wiL = reflect_about(woL, ggx_sample_visible_normal(woL, b.alpha, u1, u2));
  else wiL = sample_cosine_hemisphere(u1, u2);
  if (!(wiL.z > 0.0f)) return s;
  s.wi = to_world(wiL, n);
  float pdf = (1.0f - b.specProb) * pdf_cosine_hemisphere(wiL.z) + b.specProb * ggx_pdf(woL, wiL, b.alpha);
  if (!(pdf > 0.0f)) return s;
  float3 fcos = b.kd * (MCL_INV_PI * wiL.z) + b.ks * ggx_eval_cos(woL, wiL, b.alpha);
  s.pdf = pdf;
  s.weight = fcos * (1.0f / pdf);
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
  if (!s.smooth) return diffuse_pdf_about(b, s.ng, wo, wi);
  if (!above_surface(s.ng, wi)) return 0.0f;
  float diffuse = pdf_cosine_folded(s.ns, s.ng, wi);
  if (b.specProb == 0.0f) return diffuse;
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  float spec = woL.z > 0.0f && wiL.z > 0.0f ? ggx_pdf(woL, wiL, b.alpha) : 0.0f;
  return (1.0f - b.specProb) * diffuse + b.specProb * spec;
}

// A direction from the BSDF: wi, weight = f cos / pdf, pdf (0: absorbed).
MCL_INLINE BsdfSample diffuse_sample(DiffuseBsdf b, SurfaceFrame s, float3 wo, float u1, float u2, float uLobe) {
  if (!s.smooth) return diffuse_sample_about(b, s.ng, wo, u1, u2, uLobe);
  BsdfSample r;
  r.weight = make_float3(0.0f, 0.0f, 0.0f);
  r.pdf = 0.0f;
  r.flags = 0;
  r.wi = s.ns;
  if (b.specProb > 0.0f && uLobe < b.specProb) {
    float3 woL = to_local(wo, s.ns);
    if (!(woL.z > 0.0f)) return r;
    r.wi = to_world(reflect_about(woL, ggx_sample_visible_normal(woL, b.alpha, u1, u2)), s.ns);
  } else {
    r.wi = frame_sample_direction(s, sample_cosine_hemisphere(u1, u2));
  }
  float pdf = diffuse_pdf(b, s, wo, r.wi);
  if (!(pdf > 0.0f)) return r;
  r.pdf = pdf;
  r.weight = diffuse_eval(b, s, wo, r.wi) * (1.0f / pdf);
  return r;
}

// The direct integrator's split sample (bsdf_common.h). Lambert-only: the cosine lobe around the
// shading frame, folded above the geometric surface, always traced (its weight,
// Kd x frame_cosine_weight, is 0 where the folded pdf is). The glossy mixture: diffuse_sample's.
MCL_INLINE BsdfDirection diffuse_sample_direction(DiffuseBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                                  float uLobe) {
  BsdfDirection d;
  d.flags = 0;
  if (b.specProb == 0.0f) {
    d.wi = frame_sample_direction(s, sample_cosine_hemisphere(u1, u2));
    d.traced = 1;
    return d;
  }
  BsdfSample bs = diffuse_sample(b, s, wo, u1, u2, uLobe);
  d.wi = bs.wi;
  d.traced = bs.pdf > 0.0f;
  return d;
}

// f cos / p of a direction wi from diffuse_sample_direction whose pdf (diffuse_pdf) is pdf.
MCL_INLINE BsdfWeight diffuse_direction_weight(DiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi, float pdf) {
  BsdfWeight w;
  w.counts = b.specProb == 0.0f || pdf > 0.0f;
  w.weight = b.specProb == 0.0f ? b.kd * frame_cosine_weight(s, wi) : diffuse_eval(b, s, wo, wi) * (1.0f / pdf);
  return w;
}
