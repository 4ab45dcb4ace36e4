// bsdf.h: the surface scattering interface of the path tracer: a Bsdf built from a material, and
// bsdf_eval (f * cos), bsdf_pdf (solid angle) and bsdf_sample (direction, pdf and f * cos / pdf)
// for a shading normal n facing the outgoing direction wo. Lambertian (f = Kd / pi) for now; a
// glossy lobe plugs in here (Material::specular) without touching the stages. Pure; compiled by
// the kernels and by the host tests.
#pragma once
#include "sampling.h"
#include "types.h"

typedef struct {
  float3 kd;  // diffuse reflectance
} Bsdf;

MCL_INLINE Bsdf bsdf_make(Material m) {
  Bsdf b;
  b.kd = xyz(m.albedo);
  return b;
}

// f(wo, wi) * cos(theta_i) for unit wo, wi on the side of n (0 below the surface).
MCL_INLINE float3 bsdf_eval(Bsdf b, float3 n, float3 wo, float3 wi) {
  (void)wo;
  float c = dot(n, wi);
  return c > 0.0f ? b.kd * (c * MCL_INV_PI) : make_float3(0.0f, 0.0f, 0.0f);
}

// Solid-angle pdf with which bsdf_sample picks wi.
MCL_INLINE float bsdf_pdf(Bsdf b, float3 n, float3 wo, float3 wi) {
  (void)b;
  (void)wo;
  return pdf_cosine_hemisphere(dot(n, wi));
}

// Samples wi from (u1, u2); writes it and its pdf, returns f * cos / pdf (0 when pdf is 0).
MCL_INLINE float3 bsdf_sample(Bsdf b, float3 n, float3 wo, float u1, float u2, float3* wi, float* pdf) {
  (void)wo;
  float3 dirLocal = sample_cosine_hemisphere_portable(u1, u2);
  *wi = to_world(dirLocal, n);
  *pdf = pdf_cosine_hemisphere(dirLocal.z);
  return *pdf > 0.0f ? b.kd : make_float3(0.0f, 0.0f, 0.0f);  // (Kd / pi) cos / (cos / pi)
}
