// bsdf_metal_rough.h: the material kind "metal_rough" (material_kinds.h): glTF 2.0's
// metallic-roughness BRDF (the glTF 2.0 specification, Appendix B): a Lambertian lobe of colour
// base x (1 - metallic) weighted by (1 - F), plus a GGX lobe (alpha = roughness^2, at least
// MCL_GGX_MIN_ALPHA; shared/microfacet.h) weighted by Schlick's F = F0 + (1 - F0)(1 - |v.h|)^5 with
// F0 = mix(0.04, base, metallic); optionally under glTF's KHR_materials_clearcoat layer:
// mix(that BRDF, a GGX lobe of alpha coatRoughness^2, coat x Fc) with Fc Schlick's term of IOR 1.5
// (F0 0.04) at n.wo (the extension's fresnel_coat: n.v, not v.h, so the mix conserves energy);
// between the two (the coat is over the sheen), glTF's KHR_materials_sheen: sheenColor x the
// Charlie lobe (sheen.h) + (1 - max(sheenColor) E(n.wo)) x the base (the extension's albedo
// scaling by the view direction). Reads a Material's params0 (x: metallic, y: roughness, z, w: the
// sheen colour's r, g), specular (x: the coat factor, y: its roughness, z: the sheen colour's b, w:
// the sheen roughness) and the textured base colour (the albedo path: Kd x baseColorTexture). Pure;
// compiled by the kernels and the host tests. Sampling picks the coat's GGX lobe with probability
// pCoat (the coat's weight against the rest's), else the sheen's lobe (cosine-weighted) with
// probability pSheen (lum(sheenColor) E against the scaled base's weight), else the base's GGX lobe
// (visible normals) with probability pSpec from wo's Schlick weight and the diffuse colour; the pdf
// is the mixture. A coat factor of 0 and a sheen colour of 0 are the plain BRDF bit for bit
// (selects keep its value; the coat and the sheen are not evaluated where no lane has one). Around
// the shading normal ns; a direction below the geometric surface contributes nothing.
#pragma once
#include "bsdf_common.h"
#include "microfacet.h"
#include "sheen.h"

#define MCL_DEFINE_METAL_ROUGH_TYPE(B, F, F3) \
  typedef struct {                            \
    F3 base; /* base colour at the hit */     \
    F metallic;                               \
    F alpha; /* roughness^2 */                \
    F coat;  /* clearcoat factor, 0: none */  \
    F coatAlpha; /* clearcoat roughness^2 */  \
    F3 sheen; /* sheen colour, 0: none */     \
    F sheenRough; /* perceptual, for E */     \
    F sheenAlpha; /* sheen_alpha of it */     \
  } B;
MCL_DEFINE_METAL_ROUGH_TYPE(MetalRoughBsdf, float, float3)

// The kind's functions written once for floats and lanes (P, F, F3, M, V: the prefix, float,
// float3, int mask, f3 here; the packet stages' v_, vfloat, vfloat3, vmask, v3 in
// stages/lane_bsdf.h, with their frame FR and sample type BS): selects, not branches.
// - metal_rough_f0: F0 = mix(0.04, base, metallic); metal_rough_schlick: F0 + (1 - F0)(1 - c)^5.
// - metal_rough_lobes: the luminance of wo's specular (*ls) and diffuse (*ld) weights (cosO: local z).
// - metal_rough_spec_prob: the probability of sampling the base's GGX lobe for wo.
// - metal_rough_coated: b under a clearcoat of factor coat and roughness (0: none).
// - metal_rough_coat_weight: coat x Fc(cosO); metal_rough_coat_prob: the probability of sampling the
//   coat's lobe, its weight w against the base's (1 - w)(ls + ld); 0 without a coat.
// - metal_rough_sheened: b under a sheen of colour (r, g, bl) and roughness (colour 0: none).
// - metal_rough_sheen_prob: the probability of sampling the sheen's lobe (after the coat's), its
//   weight lum(sheen) E(cosO) against the scaled base's; 0 without a sheen.
// - metal_rough_base_eval: f cos of the plain BRDF; metal_rough_sheen_eval: that under the sheen
//   (sheened lanes of m), the plain value elsewhere.
// - metal_rough_eval, _f, _pdf, _sample: f cos, f, the mixture pdf, a direction with weight eval / pdf
//   (ANY(m): whether some lane of m is set, so the coat is skipped where no lane has one).
#define MCL_DEFINE_METAL_ROUGH(P, F, F3, M, V, ANY, B, FR, BS)                                             \
  MCL_INLINE B P##metal_rough_make(F3 base, F metallic, F roughness) {                                    \
    B b;                                                                                                  \
    b.base = base;                                                                                        \
    b.metallic = metallic;                                                                                \
    b.alpha = fmax(roughness * roughness, MCL_GGX_MIN_ALPHA);                                             \
    b.coat = (F)(0.0f);                                                                                   \
    b.coatAlpha = (F)(MCL_GGX_MIN_ALPHA);                                                                 \
    b.sheen = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                                  \
    b.sheenRough = (F)(0.0f);                                                                             \
    b.sheenAlpha = P##sheen_alpha((F)(0.0f));                                                             \
    return b;                                                                                             \
  }                                                                                                       \
  MCL_INLINE B P##metal_rough_sheened(B b, F r, F g, F bl, F roughness) {                                 \
    b.sheen = V##_make(r, g, bl);                                                                         \
    b.sheenRough = roughness;                                                                             \
    b.sheenAlpha = P##sheen_alpha(roughness);                                                             \
    return b;                                                                                             \
  }                                                                                                       \
  MCL_INLINE M P##metal_rough_has_sheen(B b) { return (b.sheen.x > 0.0f) | (b.sheen.y > 0.0f) | (b.sheen.z > 0.0f); } \
  MCL_INLINE B P##metal_rough_coated(B b, F coat, F roughness) {                                          \
    b.coat = coat;                                                                                        \
    b.coatAlpha = fmax(roughness * roughness, MCL_GGX_MIN_ALPHA);                                         \
    return b;                                                                                             \
  }                                                                                                       \
  MCL_INLINE F3 P##metal_rough_f0(B b) {                                                                  \
    return V##_add(V##_scale(V##_make((F)(0.04f), (F)(0.04f), (F)(0.04f)), 1.0f - b.metallic),            \
                   V##_scale(b.base, b.metallic));                                                        \
  }                                                                                                       \
  MCL_INLINE F3 P##metal_rough_schlick(F3 f0, F c) {                                                      \
    F m = 1.0f - fmin(fmax(c, 0.0f), 1.0f);                                                               \
    F m5 = m * m * m * m * m;                                                                             \
    return V##_add(f0, V##_scale(V##_sub(V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f)), f0), m5));            \
  }                                                                                                       \
  MCL_INLINE void P##metal_rough_lobes(B b, F cosO, F* ls, F* ld) {                                       \
    F3 fo = P##metal_rough_schlick(P##metal_rough_f0(b), cosO);                                           \
    *ls = P##luminance(fo);                                                                               \
    *ld = P##luminance(V##_mul(V##_scale(b.base, 1.0f - b.metallic),                                      \
                               V##_sub(V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f)), fo)));                  \
  }                                                                                                       \
  MCL_INLINE F P##metal_rough_spec_prob(B b, F cosO) {                                                    \
    F ls, ld;                                                                                             \
    P##metal_rough_lobes(b, cosO, &ls, &ld);                                                              \
    return vsel(ls + ld > 0.0f, fmax(ls / (ls + ld), 0.05f), (F)(1.0f));                                  \
  }                                                                                                       \
  MCL_INLINE F P##metal_rough_coat_weight(B b, F cosO) {                                                  \
    F m = 1.0f - fmin(fmax(cosO, 0.0f), 1.0f);                                                            \
    return b.coat * (0.04f + 0.96f * (m * m * m * m * m));                                                \
  }                                                                                                       \
  MCL_INLINE F P##metal_rough_sheen_weight(B b, F cosO) {                                                 \
    return P##luminance(b.sheen) * P##sheen_albedo(cosO, b.sheenRough);                                   \
  }                                                                                                       \
  MCL_INLINE F P##metal_rough_sheen_prob(B b, F cosO) {                                                   \
    F ls, ld;                                                                                             \
    P##metal_rough_lobes(b, cosO, &ls, &ld);                                                              \
    F ws = P##metal_rough_sheen_weight(b, cosO);                                                          \
    F all = ws + P##sheen_scaling(b.sheen, cosO, b.sheenRough) * (ls + ld);                               \
    return vsel(P##metal_rough_has_sheen(b) & (all > 0.0f), ws / fmax(all, 1e-30f), (F)(0.0f));           \
  }                                                                                                       \
  MCL_INLINE F P##metal_rough_coat_prob(B b, F cosO) {                                                    \
    F ls, ld;                                                                                             \
    P##metal_rough_lobes(b, cosO, &ls, &ld);                                                              \
    F w = P##metal_rough_coat_weight(b, cosO);                                                            \
    M sheened = P##metal_rough_has_sheen(b);                                                              \
    F rest = ls + ld;                                                                                     \
    if (ANY(sheened))                                                                                     \
      rest = vsel(sheened, P##metal_rough_sheen_weight(b, cosO) + P##sheen_scaling(b.sheen, cosO, b.sheenRough) * rest, rest); \
    F all = w + (1.0f - w) * rest;                                                                        \
    return vsel(all > 0.0f, w / fmax(all, 1e-30f), (F)(0.0f));                                            \
  }                                                                                                       \
  MCL_INLINE F3 P##metal_rough_base_eval(B b, FR s, F3 wo, F3 wi) {                                       \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                          \
    M ok = (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);                                  \
    F3 h = V##_normalize(V##_add(woL, wiL));                                                              \
    F3 fr = P##metal_rough_schlick(P##metal_rough_f0(b), V##_dot(woL, h));                                \
    F3 diff = V##_scale(b.base, (1.0f - b.metallic) * MCL_INV_PI * fmax(wiL.z, 0.0f));                    \
    F g = vsel(ok, P##ggx_eval_cos(woL, wiL, b.alpha), (F)(0.0f));                                        \
    F3 fcos = V##_add(V##_mul(V##_sub(V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f)), fr), diff), V##_scale(fr, g)); \
    return V##_select(ok, fcos, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                               \
  }                                                                                                       \
  MCL_INLINE F3 P##metal_rough_sheen_eval(B b, FR s, F3 wo, F3 wi, F3 fcos, M sheened) {                 \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                          \
    M ok = (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);                                  \
    F lobe = vsel(ok, P##sheen_lobe(woL, wiL, b.sheenAlpha), (F)(0.0f));                                  \
    F k = P##sheen_scaling(b.sheen, woL.z, b.sheenRough);                                                 \
    return V##_select(sheened, V##_add(V##_scale(b.sheen, lobe), V##_scale(fcos, k)), fcos);              \
  }                                                                                                       \
  MCL_INLINE F3 P##metal_rough_eval(B b, FR s, F3 wo, F3 wi) {                                            \
    F3 fcos = P##metal_rough_base_eval(b, s, wo, wi);                                                     \
    M sheened = P##metal_rough_has_sheen(b);                                                              \
    if (ANY(sheened)) fcos = P##metal_rough_sheen_eval(b, s, wo, wi, fcos, sheened);                      \
    M coated = b.coat > 0.0f;                                                                             \
    if (ANY(coated)) {                                                                                    \
      F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                        \
      M ok = (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);                                \
      F w = P##metal_rough_coat_weight(b, woL.z);                                                         \
      F g = w * vsel(ok, P##ggx_eval_cos(woL, wiL, b.coatAlpha), (F)(0.0f));                              \
      fcos = V##_select(coated, V##_add(V##_scale(fcos, 1.0f - w), V##_make(g, g, g)), fcos);             \
    }                                                                                                     \
    return fcos;                                                                                          \
  }                                                                                                       \
  MCL_INLINE F3 P##metal_rough_f(B b, FR s, F3 wo, F3 wi) {                                               \
    return P##over_cosine(P##metal_rough_eval(b, s, wo, wi), V##_dot(s.ns, wi));                          \
  }                                                                                                       \
  MCL_INLINE F P##metal_rough_pdf(B b, FR s, F3 wo, F3 wi) {                                              \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                          \
    M above = V##_dot(s.ng, wi) > 0.0f;                                                                   \
    F p = P##ggx_cosine_mix_pdf(woL, wiL, above, P##metal_rough_spec_prob(b, woL.z), b.alpha);            \
    M sheened = P##metal_rough_has_sheen(b);                                                              \
    if (ANY(sheened)) {                                                                                   \
      F ps = P##metal_rough_sheen_prob(b, woL.z);                                                         \
      M ok = above & (woL.z > 0.0f) & (wiL.z > 0.0f);                                                     \
      F q = vsel(ok, P##pdf_cosine_hemisphere(wiL.z), (F)(0.0f)); /* the sheen's cosine lobe */          \
      p = vsel(sheened, ps * q + (1.0f - ps) * p, p);                                                     \
    }                                                                                                     \
    M coated = b.coat > 0.0f;                                                                             \
    if (ANY(coated)) {                                                                                    \
      F pc = P##metal_rough_coat_prob(b, woL.z);                                                          \
      F q = P##ggx_cosine_mix_pdf(woL, wiL, above, (F)(1.0f), b.coatAlpha);                               \
      p = vsel(coated, pc * q + (1.0f - pc) * p, p);                                                      \
    }                                                                                                     \
    return p;                                                                                             \
  }                                                                                                       \
  MCL_INLINE BS P##metal_rough_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                            \
    F3 woL = P##to_local(wo, s.ns);                                                                       \
    M up = woL.z > 0.0f;                                                                                  \
    M coated = b.coat > 0.0f;                                                                             \
    F pc = (F)(0.0f);                                                                                     \
    if (ANY(coated)) pc = vsel(coated, P##metal_rough_coat_prob(b, woL.z), (F)(0.0f));                    \
    M toCoat = coated & (uLobe < pc);                                                                     \
    F uBase = vsel(coated, (uLobe - pc) / fmax(1.0f - pc, 1e-30f), uLobe);                                \
    M sheened = P##metal_rough_has_sheen(b);                                                              \
    M toSheen = (M)(0);                                                                                   \
    if (ANY(sheened)) {                                                                                   \
      F ps = vsel(sheened, P##metal_rough_sheen_prob(b, woL.z), (F)(0.0f));                               \
      toSheen = sheened & (uBase < ps);                                                                   \
      uBase = vsel(sheened, (uBase - ps) / fmax(1.0f - ps, 1e-30f), uBase);                               \
    }                                                                                                     \
    F3 wiL = P##ggx_cosine_mix_sample(woL, uBase < P##metal_rough_spec_prob(b, woL.z), b.alpha, u1, u2);  \
    if (ANY(toSheen)) wiL = V##_select(toSheen, P##sample_cosine_hemisphere(u1, u2), wiL);                \
    if (ANY(toCoat)) wiL = V##_select(toCoat, P##ggx_cosine_mix_sample(woL, toCoat, b.coatAlpha, u1, u2), wiL); \
    BS r;                                                                                                 \
    r.wi = P##to_world(wiL, s.ns);                                                                        \
    F pdf = P##metal_rough_pdf(b, s, wo, r.wi);                                                           \
    M ok = up & (pdf > 0.0f);                                                                             \
    r.pdf = vsel(ok, pdf, (F)(0.0f));                                                                     \
    r.weight = V##_select(ok, V##_scale(P##metal_rough_eval(b, s, wo, r.wi), 1.0f / fmax(pdf, 1e-30f)),   \
                          V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                     \
    r.flags = (M)(0);                                                                                     \
    return r;                                                                                             \
  }
MCL_DEFINE_METAL_ROUGH(, float, float3, int, f3, MCL_ANY1, MetalRoughBsdf, SurfaceFrame, BsdfSample)

MCL_INLINE MetalRoughBsdf metal_rough_from_material(Material m, float3 albedo) {
  MetalRoughBsdf b = metal_rough_coated(metal_rough_make(albedo, m.params0.x, m.params0.y), m.specular.x, m.specular.y);
  return metal_rough_sheened(b, m.params0.z, m.params0.w, m.specular.z, m.specular.w);
}

MCL_INLINE int metal_rough_is_delta(MetalRoughBsdf b) {
  (void)b;
  return 0;
}

// Written once for floats and lanes (lane_bsdf.h):
// - metal_rough_albedo: the albedo AOV, the diffuse colour plus F0 (the directional albedo at
//   normal incidence, approximately: base for a metal, base (1 - 0.04) + 0.04 for a dielectric),
//   under a sheen as its layer at normal incidence (sheen E(1) + the base x its scaling), under a
//   coat mixed with the coat's 0.04 by coat x 0.04 (its weight at normal incidence);
// - metal_rough_direction_weight: eval / pdf, counted where pdf > 0.
#define MCL_DEFINE_METAL_ROUGH_WEIGHTS(P, F, F3, M, V, B, FR)                                           \
  MCL_INLINE F3 P##metal_rough_albedo(B b) {                                                            \
    F3 f0 = P##metal_rough_f0(b);                                                                       \
    F3 one = V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f));                                                 \
    F3 a = V##_add(V##_mul(V##_scale(b.base, 1.0f - b.metallic), V##_sub(one, f0)), f0);                \
    F3 sheened = V##_add(V##_scale(b.sheen, P##sheen_albedo((F)(1.0f), b.sheenRough)),                  \
                         V##_scale(a, P##sheen_scaling(b.sheen, (F)(1.0f), b.sheenRough)));             \
    a = V##_select(P##metal_rough_has_sheen(b), sheened, a);                                            \
    F w = b.coat * 0.04f;                                                                               \
    F3 coated = V##_add(V##_scale(a, 1.0f - w), V##_make(w, w, w));                                     \
    return V##_select(b.coat > 0.0f, coated, a);                                                        \
  }                                                                                                     \
  MCL_INLINE F3 P##metal_rough_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {            \
    *counts = pdf > 0.0f;                                                                               \
    return V##_scale(P##metal_rough_eval(b, s, wo, wi), 1.0f / fmax(pdf, 1e-30f));                      \
  }
MCL_DEFINE_METAL_ROUGH_WEIGHTS(, float, float3, int, f3, MetalRoughBsdf, SurfaceFrame)
