// bsdf.h: the surface model of every shade stage: a Lambertian lobe (Kd) plus a GGX glossy lobe
// (Ks, roughness alpha; shared/microfacet.h), in world space around a unit normal n that faces wo.
// Conventions: wo points from the surface toward the viewer, wi toward the light, both unit.
//   bsdf_f(b, n, wo, wi)        f (no cosine); 0 when wi or wo is below the surface
//   bsdf_eval(b, n, wo, wi)     f * cos(n, wi)
//   bsdf_pdf(b, n, wo, wi)      solid-angle pdf of bsdf_sample producing wi
//   bsdf_sample(b, n, wo, u1, u2, uLobe)   wi, weight = f cos / pdf, pdf (pdf 0: no sample)
// The lobe is picked with probability proportional to its luminance (Kd vs Ks); the pdf is the
// mixture of both lobes' pdfs (one-sample MIS over lobes). With Ks = 0 every function reduces to
// the Lambertian expressions, operation for operation (Lambert-only images are bit-identical to
// the renderer before the glossy lobe). Kd + Ks <= 1 is ensured at load (energy conservation).
// Pure; compiled by the kernels and by the host tests.
#pragma once
#include "lights.h"
#include "microfacet.h"

typedef struct {
  float3 kd;        // Lambertian reflectance
  float3 ks;        // glossy reflectance
  float alpha;      // GGX roughness
  float specProb;   // probability of sampling the glossy lobe; 0 = Lambertian only
} Bsdf;

MCL_INLINE Bsdf bsdf_make(float3 kd, float3 ks, float alpha) {
  Bsdf b;
  b.kd = kd;
  b.ks = ks;
  b.alpha = fmax(alpha, MCL_GGX_MIN_ALPHA);
  float ls = luminance(ks), ld = luminance(kd);
  b.specProb = ls > 0.0f ? ls / (ls + ld) : 0.0f;
  return b;
}

// A device material's lobes (albedo texture lookups, if any, replace kd afterwards).
MCL_INLINE Bsdf bsdf_from_material(MCL_GLOBAL const Material* m) {
  return bsdf_make(xyz(m->albedo), xyz(m->specular), m->specular.w);
}

// Local coordinates of w in the frame (t, b, n) of make_basis.
MCL_INLINE float3 to_local(float3 w, float3 n) {
  float3 t, b;
  make_basis(n, &t, &b);
  return make_float3(dot(w, t), dot(w, b), dot(w, n));
}

MCL_INLINE float3 bsdf_f(Bsdf b, float3 n, float3 wo, float3 wi) {
  float cosI = dot(n, wi);
  if (b.specProb == 0.0f) return cosI > 0.0f ? b.kd * MCL_INV_PI : make_float3(0.0f, 0.0f, 0.0f);
  float cosO = dot(n, wo);
  if (!(cosI > 0.0f && cosO > 0.0f)) return make_float3(0.0f, 0.0f, 0.0f);
  float g = ggx_eval_cos(to_local(wo, n), to_local(wi, n), b.alpha) / cosI;
  return b.kd * MCL_INV_PI + b.ks * g;
}

MCL_INLINE float3 bsdf_eval(Bsdf b, float3 n, float3 wo, float3 wi) {
  float c = dot(n, wi);
  if (b.specProb == 0.0f) return c > 0.0f ? b.kd * (c * MCL_INV_PI) : make_float3(0.0f, 0.0f, 0.0f);
  return bsdf_f(b, n, wo, wi) * fmax(c, 0.0f);
}

MCL_INLINE float bsdf_pdf(Bsdf b, float3 n, float3 wo, float3 wi) {
  float cosI = dot(n, wi);
  if (b.specProb == 0.0f) return pdf_cosine_hemisphere(cosI);
  if (!(cosI > 0.0f && dot(n, wo) > 0.0f)) return 0.0f;
  return (1.0f - b.specProb) * pdf_cosine_hemisphere(cosI) +
         b.specProb * ggx_pdf(to_local(wo, n), to_local(wi, n), b.alpha);
}

typedef struct {
  float3 wi;
  float3 weight;  // f * cos / pdf
  float pdf;      // 0: no direction (the sample is absorbed)
} BsdfSample;

MCL_INLINE BsdfSample bsdf_sample(Bsdf b, float3 n, float3 wo, float u1, float u2, float uLobe) {
  BsdfSample s;
  if (b.specProb == 0.0f) {  // Lambertian: f cos / p = Kd exactly
    float3 dirLocal = sample_cosine_hemisphere(u1, u2);  // sampling.h: same bits on every device
    s.wi = to_world(dirLocal, n);
    s.pdf = pdf_cosine_hemisphere(dirLocal.z);
    s.weight = s.pdf > 0.0f ? b.kd : make_float3(0.0f, 0.0f, 0.0f);
    return s;
  }
  float3 woL = to_local(wo, n);
  s.weight = make_float3(0.0f, 0.0f, 0.0f);
  s.pdf = 0.0f;
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
