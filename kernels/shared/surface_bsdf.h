// surface_bsdf.h: the BSDF (bsdf.h: Lambert Kd + GGX Ks) at a hit with a shading frame (shading.h),
// for every shade stage. Without shading normals (s.smooth == 0) each function is bsdf.h's around
// the geometric normal, operation for operation. With them: the lobes are built around the
// shading normal ns; a direction below the geometric surface contributes nothing (f = 0, pdf = 0:
// no light leaks); the Lambertian lobe's samples that fall below the geometric surface are folded
// above it (shading.h, pdf_cosine_folded), while a glossy sample below it is absorbed (pdf of the
// glossy lobe is its plain density above the surface, so the mixture pdf stays exact).
// Pure; compiled by the kernels and by the host tests.
#pragma once
#include "bsdf.h"
#include "shading.h"

// f (no cosine) for wo, wi (unit; wo toward the viewer, wi toward the light).
MCL_INLINE float3 surface_bsdf_f(Bsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  if (!s.smooth) return bsdf_f(b, s.ng, wo, wi);
  if (!above_surface(s.ng, wi)) return make_float3(0.0f, 0.0f, 0.0f);
  return bsdf_f(b, s.ns, wo, wi);
}

// f * cos(ns, wi), zero below the geometric surface.
MCL_INLINE float3 surface_bsdf_eval(Bsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  if (!s.smooth) return bsdf_eval(b, s.ng, wo, wi);
  if (!above_surface(s.ng, wi)) return make_float3(0.0f, 0.0f, 0.0f);
  return bsdf_eval(b, s.ns, wo, wi);
}

// Solid-angle pdf of surface_bsdf_sample producing wi.
MCL_INLINE float surface_bsdf_pdf(Bsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  if (!s.smooth) return bsdf_pdf(b, s.ng, wo, wi);
  if (!above_surface(s.ng, wi)) return 0.0f;
  float diffuse = pdf_cosine_folded(s.ns, s.ng, wi);
  if (b.specProb == 0.0f) return diffuse;
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  float spec = woL.z > 0.0f && wiL.z > 0.0f ? ggx_pdf(woL, wiL, b.alpha) : 0.0f;
  return (1.0f - b.specProb) * diffuse + b.specProb * spec;
}

// A direction from the BSDF: wi, weight = f cos / pdf, pdf (0: absorbed).
MCL_INLINE BsdfSample surface_bsdf_sample(Bsdf b, SurfaceFrame s, float3 wo, float u1, float u2, float uLobe) {
  if (!s.smooth) return bsdf_sample(b, s.ng, wo, u1, u2, uLobe);
  BsdfSample r;
  r.weight = make_float3(0.0f, 0.0f, 0.0f);
  r.pdf = 0.0f;
  r.wi = s.ns;
  if (b.specProb > 0.0f && uLobe < b.specProb) {
    float3 woL = to_local(wo, s.ns);
    if (!(woL.z > 0.0f)) return r;
    r.wi = to_world(reflect_about(woL, ggx_sample_visible_normal(woL, b.alpha, u1, u2)), s.ns);
  } else {
    r.wi = frame_sample_direction(s, sample_cosine_hemisphere(u1, u2));
  }
  float pdf = surface_bsdf_pdf(b, s, wo, r.wi);
  if (!(pdf > 0.0f)) return r;
  r.pdf = pdf;
  r.weight = surface_bsdf_eval(b, s, wo, r.wi) * (1.0f / pdf);
  return r;
}
