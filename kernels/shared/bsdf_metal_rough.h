// bsdf_metal_rough.h: the material kind "metal_rough" (material_kinds.h): glTF 2.0's
// metallic-roughness BRDF (the glTF 2.0 specification, Appendix B): a Lambertian lobe of colour
// base x (1 - metallic) weighted by (1 - F), plus a GGX lobe (alpha = roughness^2, at least
// MCL_GGX_MIN_ALPHA; shared/microfacet.h) weighted by Schlick's F = F0 + (1 - F0)(1 - |v.h|)^5 with
// F0 = mix(0.04, base, metallic). Reads a Material's params0 (x: metallic, y: roughness) and the
// textured base colour (the albedo path: Kd x baseColorTexture). Pure; compiled by the kernels and
// the host tests. Sampling picks the GGX lobe (visible normals) with probability pSpec from wo's
// Schlick weight and the diffuse colour; the pdf is the mixture. Around the shading normal ns; a
// direction below the geometric surface contributes nothing. Written with selects.
#pragma once
#include "bsdf_common.h"
#include "microfacet.h"

typedef struct {
  float3 base;  // base colour at the hit
  float metallic;
  float alpha;  // roughness^2
} MetalRoughBsdf;

MCL_INLINE MetalRoughBsdf metal_rough_make(float3 base, float metallic, float roughness) {
  MetalRoughBsdf b;
  b.base = base;
  b.metallic = metallic;
  b.alpha = fmax(roughness * roughness, MCL_GGX_MIN_ALPHA);
  return b;
}

MCL_INLINE MetalRoughBsdf metal_rough_from_material(Material m, float3 albedo) {
  return metal_rough_make(albedo, m.params0.x, m.params0.y);
}

MCL_INLINE int metal_rough_is_delta(MetalRoughBsdf b) {
  (void)b;
  return 0;
}

MCL_INLINE float3 metal_rough_f0(MetalRoughBsdf b) {
  return make_float3(0.04f, 0.04f, 0.04f) * (1.0f - b.metallic) + b.base * b.metallic;
}

MCL_INLINE float3 metal_rough_schlick(float3 f0, float c) {
  float m = 1.0f - fmin(fmax(c, 0.0f), 1.0f);
  float m5 = m * m * m * m * m;
  return f0 + (make_float3(1.0f, 1.0f, 1.0f) - f0) * m5;
}

// The albedo AOV: the diffuse colour plus F0 (the directional albedo at normal incidence,
// approximately: base for a metal, base (1 - 0.04) + 0.04 for a dielectric).
MCL_INLINE float3 metal_rough_albedo(MetalRoughBsdf b) {
  float3 f0 = metal_rough_f0(b);
  return b.base * (1.0f - b.metallic) * (make_float3(1.0f, 1.0f, 1.0f) - f0) + f0;
}

// Probability of sampling the GGX lobe for wo (local z = cosO).
MCL_INLINE float metal_rough_spec_prob(MetalRoughBsdf b, float cosO) {
  float3 fo = metal_rough_schlick(metal_rough_f0(b), cosO);
  float ls = luminance(fo);
  float ld = luminance(b.base * (1.0f - b.metallic) * (make_float3(1.0f, 1.0f, 1.0f) - fo));
  return ls + ld > 0.0f ? fmax(ls / (ls + ld), 0.05f) : 1.0f;
}

MCL_INLINE float3 metal_rough_eval(MetalRoughBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  int ok = above_surface(s.ng, wi) && woL.z > 0.0f && wiL.z > 0.0f;
  float3 h = normalize(woL + wiL);
  float3 F = metal_rough_schlick(metal_rough_f0(b), dot(woL, h));
  float3 diff = b.base * ((1.0f - b.metallic) * MCL_INV_PI * fmax(wiL.z, 0.0f));
  float g = ok ? ggx_eval_cos(woL, wiL, b.alpha) : 0.0f;
  float3 fcos = (make_float3(1.0f, 1.0f, 1.0f) - F) * diff + F * g;
  return ok ? fcos : make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float3 metal_rough_f(MetalRoughBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float c = dot(s.ns, wi);
  return c > 0.0f ? metal_rough_eval(b, s, wo, wi) * (1.0f / c) : make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float metal_rough_pdf(MetalRoughBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  return ggx_cosine_mix_pdf(woL, wiL, above_surface(s.ng, wi), metal_rough_spec_prob(b, woL.z), b.alpha);
}

MCL_INLINE BsdfSample metal_rough_sample(MetalRoughBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                         float uLobe) {
  float3 woL = to_local(wo, s.ns);
  int up = woL.z > 0.0f;
  float3 wiL = ggx_cosine_mix_sample(woL, uLobe < metal_rough_spec_prob(b, woL.z), b.alpha, u1, u2);
  BsdfSample r;
  r.wi = to_world(wiL, s.ns);
  float pdf = metal_rough_pdf(b, s, wo, r.wi);
  int ok = up && pdf > 0.0f;
  r.pdf = ok ? pdf : 0.0f;
  r.weight = ok ? metal_rough_eval(b, s, wo, r.wi) * (1.0f / fmax(pdf, 1e-30f)) : make_float3(0.0f, 0.0f, 0.0f);
  r.flags = 0;
  return r;
}

MCL_INLINE BsdfDirection metal_rough_sample_direction(MetalRoughBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                                      float uLobe) {
  return bsdf_direction_of(metal_rough_sample(b, s, wo, u1, u2, uLobe));
}

MCL_INLINE BsdfWeight metal_rough_direction_weight(MetalRoughBsdf b, SurfaceFrame s, float3 wo, float3 wi, float pdf) {
  BsdfWeight w;
  w.counts = pdf > 0.0f;
  w.weight = metal_rough_eval(b, s, wo, wi) * (1.0f / fmax(pdf, 1e-30f));
  return w;
}
