// microfacet.h: the GGX (Trowbridge-Reitz) microfacet reflection lobe in a local frame (z = the
// shading normal): normal distribution D, Smith masking G1 and height-correlated G2, visible-normal
// sampling (Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 2018) and its pdf.
// No Fresnel term: the lobe's colour is Ks, so f = Ks D G2 / (4 cos_o cos_i) reflects at most Ks
// (single scattering loses the rest). Roughness from an OBJ exponent: alpha = sqrt(2 / (Ns + 2))
// (the Beckmann-Phong equivalence of Walter et al. 2007), clamped to at least MCL_GGX_MIN_ALPHA.
// Pure; compiled by the kernels and by the host tests.
#pragma once
#include "sampling.h"
#include "trig.h"

#define MCL_GGX_MIN_ALPHA 1e-3f

MCL_INLINE float ggx_alpha_from_ns(float ns) { return fmax(sqrt(2.0f / (ns + 2.0f)), MCL_GGX_MIN_ALPHA); }

// D(h): density of microfacet normals per unit projected area (h local, unit).
MCL_INLINE float ggx_d(float3 h, float alpha) {
  if (!(h.z > 0.0f)) return 0.0f;
  float a2 = alpha * alpha;
  float t = h.z * h.z * (a2 - 1.0f) + 1.0f;
  return a2 / (MCL_PI * t * t);
}

// Smith's Lambda for GGX: (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2.
MCL_INLINE float ggx_lambda(float3 w, float alpha) {
  float z2 = w.z * w.z;
  float s2 = w.x * w.x + w.y * w.y;
  if (!(z2 > 0.0f)) return 1e30f;
  return 0.5f * (-1.0f + sqrt(1.0f + alpha * alpha * s2 / z2));
}
MCL_INLINE float ggx_g1(float3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
MCL_INLINE float ggx_g2(float3 wo, float3 wi, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// f * cos(theta_i) of the lobe with unit colour: D G2 / (4 cos_o); 0 unless both are above.
MCL_INLINE float ggx_eval_cos(float3 wo, float3 wi, float alpha) {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  float3 h = normalize(wo + wi);
  return ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z);
}

// A visible normal for wo (wo.z > 0) from u1, u2 in [0, 1): Heitz 2018, section 2: stretch wo to
// the hemisphere configuration, sample a projected disk warped toward wo, unstretch.
MCL_INLINE float3 ggx_sample_visible_normal(float3 wo, float alpha, float u1, float u2) {
  float3 vh = normalize(make_float3(alpha * wo.x, alpha * wo.y, wo.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  float3 t1 = lensq > 0.0f ? make_float3(-vh.y, vh.x, 0.0f) * (1.0f / sqrt(lensq)) : make_float3(1.0f, 0.0f, 0.0f);
  float3 t2 = cross(vh, t1);
  float r = sqrt(u1);
  float sinPhi, cosPhi;
  mcl_sincos_turns(u2, &sinPhi, &cosPhi);  // phi = 2 pi u2
  float p1 = r * cosPhi, p2 = r * sinPhi;
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * p2;
  float3 nh = t1 * p1 + t2 * p2 + vh * sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(make_float3(alpha * nh.x, alpha * nh.y, fmax(1e-7f, nh.z)));
}

// Solid-angle pdf of wi = reflect(wo about h) under visible-normal sampling:
// D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z).
MCL_INLINE float ggx_pdf(float3 wo, float3 wi, float alpha) {
  if (!(wo.z > 0.0f && wi.z > 0.0f)) return 0.0f;
  float3 h = normalize(wo + wi);
  return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z);
}

// Mirror of w about the unit normal h.
MCL_INLINE float3 reflect_about(float3 w, float3 h) { return h * (2.0f * dot(w, h)) - w; }

// A cosine lobe mixed with a GGX reflection lobe picked with probability ps (the kinds with a
// diffuse base under a glossy lobe: metal_rough, coated_diffuse), in the shading frame (woL, wiL;
// above: wi lies above the geometric surface). The mixture's solid-angle pdf, and the direction
// drawn from the lobe `glossy` names.
MCL_INLINE float ggx_cosine_mix_pdf(float3 woL, float3 wiL, int above, float ps, float alpha) {
  int ok = above && woL.z > 0.0f && wiL.z > 0.0f;
  float p = (1.0f - ps) * pdf_cosine_hemisphere(wiL.z) + ps * (ok ? ggx_pdf(woL, wiL, alpha) : 0.0f);
  return ok ? p : 0.0f;
}
MCL_INLINE float3 ggx_cosine_mix_sample(float3 woL, int glossy, float alpha, float u1, float u2) {
  float3 hL = woL.z > 0.0f ? ggx_sample_visible_normal(woL, alpha, u1, u2) : make_float3(0.0f, 0.0f, 1.0f);
  return glossy ? reflect_about(woL, hL) : sample_cosine_hemisphere(u1, u2);
}
