// microfacet_beckmann.h: the Beckmann microfacet reflection lobe in a local frame (z = the shading
// normal), beside microfacet.h's GGX: normal distribution D, Smith's Lambda and the
// height-correlated G2. Tungsten's and Mitsuba's rough conductors default to it (Mitsuba's
// distribution "beckmann"); pbrt-v4 has only GGX. Lambda is Walter et al. 2007's rational fit
// (within 0.35% of the exact erf form; Tungsten and Mitsuba use it too), so the lobe needs only
// + - * / sqrt and exp_neg: the same bits on every device. No sampler of its own: GGX's
// visible normals of the same alpha are its proposal (D_beckmann / D_ggx = e^-x (1 + x)^2 with
// x = tan^2 / alpha^2, at most 4 / e, so the weights stay bounded). Pure; compiled by the kernels and
// by the host tests.
#pragma once
#include "exp_neg.h"
#include "microfacet.h"

// Written once for floats and lanes (P, E, F, F3, V: the prefix, exp_neg's prefix, float, float3,
// f3 here; v_, v_, vfloat, vfloat3, v3 in stages/lane_bsdf.h), selects rather than branches:
// - beckmann_d(h) = exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4) (h local, unit; 0 below).
// - beckmann_lambda: a = 1 / (alpha tan theta); (1 - 1.259 a + 0.396 a^2) / (3.535 a + 2.181 a^2)
//   below a = 1.6, else 0.
// - beckmann_eval_cos: f * cos(theta_i) of the lobe with unit colour, D G2 / (4 cos_o); 0 unless
//   both are above.
#define MCL_DEFINE_BECKMANN(P, E, F, F3, V)                                                        \
  MCL_INLINE F P##beckmann_d(F3 h, F alpha) {                                                      \
    F c2 = h.z * h.z;                                                                              \
    F a2 = alpha * alpha;                                                                          \
    F t2 = fmax(1.0f - c2, 0.0f) / fmax(c2, 1e-30f);                                               \
    F d = E##exp_neg(t2 / a2) / (MCL_PI * a2 * c2 * c2);                                           \
    return vsel(h.z > 0.0f, d, (F)(0.0f));                                                         \
  }                                                                                                \
  MCL_INLINE F P##beckmann_lambda(F3 w, F alpha) {                                                 \
    F z2 = w.z * w.z;                                                                              \
    F s2 = w.x * w.x + w.y * w.y;                                                                  \
    F a = sqrt(z2 / fmax(s2, 1e-30f)) / alpha;                                                     \
    F l = (1.0f - 1.259f * a + 0.396f * a * a) / (3.535f * a + 2.181f * a * a);                    \
    return vsel(z2 > 0.0f, vsel(a < 1.6f, l, (F)(0.0f)), (F)(1e30f));                              \
  }                                                                                                \
  MCL_INLINE F P##beckmann_eval_cos(F3 wo, F3 wi, F alpha) {                                       \
    F3 h = V##_normalize(V##_add(wo, wi));                                                         \
    F g2 = 1.0f / (1.0f + P##beckmann_lambda(wo, alpha) + P##beckmann_lambda(wi, alpha));          \
    F v = P##beckmann_d(h, alpha) * g2 / (4.0f * wo.z);                                            \
    return vsel((wo.z > 0.0f) & (wi.z > 0.0f), v, (F)(0.0f));                                      \
  }
MCL_DEFINE_BECKMANN(, mcl_, float, float3, f3)
