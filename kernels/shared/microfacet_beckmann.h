// microfacet_beckmann.h: the Beckmann microfacet reflection lobe in a local frame (z = the shading
// normal), beside microfacet.h's GGX: normal distribution D, Smith's Lambda and the
// height-correlated G2. Tungsten's and Mitsuba's rough conductors default to it (Mitsuba's
// distribution "beckmann"); pbrt-v4 has only GGX. Lambda is Walter et al. 2007's rational fit
// (within 0.35% of the exact erf form; Tungsten and Mitsuba use it too), so the lobe needs only
// + - * / sqrt and mcl_exp_neg: the same bits on every device. No sampler of its own: GGX's
// visible normals of the same alpha are its proposal (D_beckmann / D_ggx = e^-x (1 + x)^2 with
// x = tan^2 / alpha^2, at most 4 / e, so the weights stay bounded). Pure; compiled by the kernels and
// by the host tests.
#pragma once
#include "exp_neg.h"
#include "microfacet.h"

// D(h) = exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4) (h local, unit).
MCL_INLINE float beckmann_d(float3 h, float alpha) {
  float c2 = h.z * h.z;
  float a2 = alpha * alpha;
  float t2 = fmax(1.0f - c2, 0.0f) / fmax(c2, 1e-30f);
  float d = mcl_exp_neg(t2 / a2) / (MCL_PI * a2 * c2 * c2);
  return h.z > 0.0f ? d : 0.0f;
}

// Smith's Lambda: a = 1 / (alpha tan theta); (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2)
// below a = 1.6, else 0.
MCL_INLINE float beckmann_lambda(float3 w, float alpha) {
  float z2 = w.z * w.z;
  float s2 = w.x * w.x + w.y * w.y;
  float a = sqrt(z2 / fmax(s2, 1e-30f)) / alpha;
  float l = (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);
  return z2 > 0.0f ? (a < 1.6f ? l : 0.0f) : 1e30f;
}

// f * cos(theta_i) of the lobe with unit colour: D G2 / (4 cos_o); 0 unless both are above.
MCL_INLINE float beckmann_eval_cos(float3 wo, float3 wi, float alpha) {
  float3 h = normalize(wo + wi);
  float g2 = 1.0f / (1.0f + beckmann_lambda(wo, alpha) + beckmann_lambda(wi, alpha));
  float v = beckmann_d(h, alpha) * g2 / (4.0f * wo.z);
  return wo.z > 0.0f && wi.z > 0.0f ? v : 0.0f;
}
