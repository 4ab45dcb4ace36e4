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

// The lobe written once for a float type F, its 3-vector F3 with that vector's operations V and
// trig.h's sine and cosine of prefix S (float, float3, f3, mcl_ here; the packet stages' vfloat,
// vfloat3, v3, v_ in stages/lane_bsdf.h): selects (vsel), not branches, so each lane performs the
// scalar function's operations in the same order.
// - ggx_d(h): density of microfacet normals per unit projected area (h local, unit; 0 below).
// - ggx_lambda(w): Smith's Lambda for GGX, (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2; ggx_g1, ggx_g2
//   (height-correlated) from it.
// - ggx_eval_cos: f * cos(theta_i) of the lobe with unit colour, D G2 / (4 cos_o); 0 unless wo and
//   wi are both above.
// - ggx_sample_visible_normal: a visible normal for wo (wo.z > 0) from u1, u2 in [0, 1): Heitz
//   2018, section 2: stretch wo to the hemisphere configuration, sample a projected disk warped
//   toward wo, unstretch.
// - ggx_pdf: solid-angle pdf of wi = reflect(wo about h) under visible-normal sampling,
//   D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z).
// - reflect_about: the mirror of w about the unit normal h.
// - ggx_cosine_mix_pdf, ggx_cosine_mix_sample: a cosine lobe mixed with a GGX reflection lobe
//   picked with probability ps (the kinds with a diffuse base under a glossy lobe: metal_rough,
//   coated_diffuse), in the shading frame (woL, wiL; above: wi lies above the geometric surface):
//   the mixture's solid-angle pdf, and the direction drawn from the lobe `glossy` names (M: the
//   mask type of F).
#define MCL_DEFINE_GGX(P, S, F, F3, M, V)                                                                         \
  MCL_INLINE F P##ggx_d(F3 h, F alpha) {                                                                      \
    F a2 = alpha * alpha;                                                                                      \
    F t = h.z * h.z * (a2 - 1.0f) + 1.0f;                                                                      \
    return vsel(h.z > 0.0f, a2 / (MCL_PI * t * t), (F)(0.0f));                                                 \
  }                                                                                                            \
  MCL_INLINE F P##ggx_lambda(F3 w, F alpha) {                                                                 \
    F z2 = w.z * w.z;                                                                                          \
    F s2 = w.x * w.x + w.y * w.y;                                                                              \
    return vsel(z2 > 0.0f, 0.5f * (-1.0f + sqrt(1.0f + alpha * alpha * s2 / z2)), (F)(1e30f));                \
  }                                                                                                            \
  MCL_INLINE F P##ggx_g1(F3 w, F alpha) { return 1.0f / (1.0f + P##ggx_lambda(w, alpha)); }                   \
  MCL_INLINE F P##ggx_g2(F3 wo, F3 wi, F alpha) {                                                             \
    return 1.0f / (1.0f + P##ggx_lambda(wo, alpha) + P##ggx_lambda(wi, alpha));                                \
  }                                                                                                            \
  MCL_INLINE F P##ggx_eval_cos(F3 wo, F3 wi, F alpha) {                                                       \
    F3 h = V##_normalize(V##_add(wo, wi));                                                                     \
    F r = P##ggx_d(h, alpha) * P##ggx_g2(wo, wi, alpha) / (4.0f * wo.z);                                       \
    return vsel((wo.z > 0.0f) & (wi.z > 0.0f), r, (F)(0.0f));                                                  \
  }                                                                                                            \
  MCL_INLINE F3 P##ggx_sample_visible_normal(F3 wo, F alpha, F u1, F u2) {                                    \
    F3 vh = V##_normalize(V##_make(alpha * wo.x, alpha * wo.y, wo.z));                                         \
    F lensq = vh.x * vh.x + vh.y * vh.y;                                                                       \
    F3 t1 = V##_select(lensq > 0.0f, V##_scale(V##_make(-vh.y, vh.x, (F)(0.0f)), 1.0f / sqrt(lensq)),          \
                       V##_make((F)(1.0f), (F)(0.0f), (F)(0.0f)));                                             \
    F3 t2 = V##_cross(vh, t1);                                                                                 \
    F r = sqrt(u1);                                                                                            \
    F sinPhi, cosPhi;                                                                                          \
    S##sincos_turns(u2, &sinPhi, &cosPhi); /* phi = 2 pi u2 */                                                 \
    F p1 = r * cosPhi, p2 = r * sinPhi;                                                                        \
    F s = 0.5f * (1.0f + vh.z);                                                                                \
    p2 = (1.0f - s) * sqrt(fmax((F)(0.0f), 1.0f - p1 * p1)) + s * p2;                                          \
    F3 nh = V##_add(V##_add(V##_scale(t1, p1), V##_scale(t2, p2)),                                             \
                    V##_scale(vh, sqrt(fmax((F)(0.0f), 1.0f - p1 * p1 - p2 * p2))));                           \
    return V##_normalize(V##_make(alpha * nh.x, alpha * nh.y, fmax((F)(1e-7f), nh.z)));                        \
  }                                                                                                            \
  MCL_INLINE F P##ggx_pdf(F3 wo, F3 wi, F alpha) {                                                            \
    F3 h = V##_normalize(V##_add(wo, wi));                                                                     \
    F r = P##ggx_g1(wo, alpha) * P##ggx_d(h, alpha) / (4.0f * wo.z);                                           \
    return vsel((wo.z > 0.0f) & (wi.z > 0.0f), r, (F)(0.0f));                                                  \
  }                                                                                                            \
  MCL_INLINE F3 P##reflect_about(F3 w, F3 h) { return V##_sub(V##_scale(h, 2.0f * V##_dot(w, h)), w); }    \
  MCL_INLINE F P##ggx_cosine_mix_pdf(F3 woL, F3 wiL, M above, F ps, F alpha) {                                \
    M ok = above & (woL.z > 0.0f) & (wiL.z > 0.0f);                                                            \
    F p = (1.0f - ps) * P##pdf_cosine_hemisphere(wiL.z) + ps * vsel(ok, P##ggx_pdf(woL, wiL, alpha), (F)(0.0f)); \
    return vsel(ok, p, (F)(0.0f));                                                                             \
  }                                                                                                            \
  MCL_INLINE F3 P##ggx_cosine_mix_sample(F3 woL, M glossy, F alpha, F u1, F u2) {                             \
    F3 hL = V##_select(woL.z > 0.0f, P##ggx_sample_visible_normal(woL, alpha, u1, u2),                         \
                       V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f)));                                             \
    return V##_select(glossy, P##reflect_about(woL, hL), P##sample_cosine_hemisphere(u1, u2));                 \
  }
MCL_DEFINE_GGX(, mcl_, float, float3, int, f3)

