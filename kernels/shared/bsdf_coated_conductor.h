// bsdf_coated_conductor.h: the material kind "coated_conductor" (material_kinds.h): a dielectric
// coat of index ior over a conductor base of complex index eta + i k and GGX roughness, a clear
// layer of some thickness between them; pbrt-v4's coatedconductor (its LayeredBxDF with a
// dielectric top and a conductor bottom), evaluated stochastically as coated_diffuse is. Reads a
// Material's params0 (xyz: the metal's eta, w: the base's GGX alpha), params1 (xyz: k, w: the
// coat's GGX alpha) and specular (x: ior, y: thickness, z: the walk's bounce limit, w: walks per
// evaluation, both as uint bits). Pure; compiled by the kernels and the host tests.
//
// As in pbrt-v4, the metal's eta and k are divided by the coat's index (the metal borders the coat,
// not the outside). f = the coat's own reflection (GGX of alpha at least MCL_GGX_MIN_ALPHA times
// the dielectric Fresnel of wo.h) + light that crosses the coat, walks between the base and the
// coat's underside and crosses out again. The interface is flat for the light inside the layer (as
// in coated_diffuse: the coat's roughness shapes only its own reflection), so a direction w outside
// is (w.xy / ior, cos_t) inside and the walk is a chain of base reflections: it enters along wo
// (radiance scaled by T(wo) / ior^2), at every visit of the base adds the path out toward wi (the
// GGX conductor f of the two inside directions, the layer's transmittance, T(wi)), then reflects
// by a visible normal of the base (weight F G2 / G1) and, at the coat's underside, by its Fresnel
// F (total internal reflection: 1), which mirrors the direction's height. Each crossing is
// attenuated by exp(-thickness / |cos|); Russian roulette as coated_diffuse's. A smooth base
// (alpha 0) is a GGX lobe of alpha MCL_GGX_MIN_ALPHA, so the kind has no delta lobe. No scattering
// medium in the layer (pbrt's albedo, g: the loaders warn).
//
// Sampling: the coat's GGX lobe with probability F(wo) clamped to [0.1, 0.9], else the base's: wo
// refracted in, a visible normal of the base, the reflection refracted out (total internal
// reflection: no sample). pdf is that exact mixture (the base lobe's inside density times the
// refraction's solid-angle ratio cos_o / (ior^2 cos_t)); the weight is eval / pdf with eval's
// estimate, unbiased because eval is.
#pragma once
#include "bsdf_coated_diffuse.h"
#include "bsdf_common.h"
#include "microfacet.h"
#include "rng.h"

#define MCL_DEFINE_COATED_CONDUCTOR_TYPE(B, F, F3, U)                   \
  typedef struct {                                                       \
    F3 eta, k;    /* the metal's index relative to the coat */           \
    F baseAlpha;  /* the base's GGX alpha (at least MCL_GGX_MIN_ALPHA) */ \
    F alpha;      /* the coat's GGX alpha */                             \
    F ior;        /* the coat's index (inside / outside) */              \
    F thickness;  /* of the clear layer */                               \
    U maxDepth;   /* scattering events per walk */                       \
    U samples;    /* walks per evaluation */                             \
  } B;
MCL_DEFINE_COATED_CONDUCTOR_TYPE(CoatedConductorBsdf, float, float3, uint)

// The kind's functions written once for floats and lanes (the parameters as coated_diffuse's
// macro: P, F, F3, M, U, V, ANY, the frame FR, sample type BS, random-number type RO, PCG, UNIT,
// the uint -> float conversion CVT_F_U, exp_neg's prefix E). A lane's walk stops (its mask clears) where the scalar walk breaks; the
// walks run while some lane's does.
// - coated_conductor_make: from the Material's fields (eta and k before the division by ior).
// - coated_conductor_inside: a local direction w (w.z > 0) outside as the layer sees it: (w.xy /
//   ior, cos of the refraction).
// - coated_conductor_base_f: the base's GGX conductor f (no cosine) between two inside directions.
// - coated_conductor_walk: one walk's estimate of the through-the-coat part of f (no cosine) for
//   local directions woL, wiL (z > 0) with numbers from pcg4d(seed, step), in the lanes of `live`.
// - coated_conductor_eval, _f, _coat_prob, _pdf, _sample: f cos (the coat's GGX reflection plus the
//   walks' mean), f, the coat lobe's probability, the mixture pdf, a direction with weight eval / pdf.
#define MCL_DEFINE_COATED_CONDUCTOR(P, F, F3, M, U, V, ANY, B, FR, BS, RO, PCG, UNIT, CVT_F_U, E)                         \
  MCL_INLINE B P##coated_conductor_make(F3 eta, F3 k, F baseAlpha, F alpha, F ior, F thickness, U maxDepth,       \
                                        U samples) {                                                            \
    B b;                                                                                                        \
    b.ior = ior;                                                                                                \
    b.eta = V##_scale(eta, 1.0f / b.ior);                                                                       \
    b.k = V##_scale(k, 1.0f / b.ior);                                                                           \
    b.baseAlpha = fmax(baseAlpha, MCL_GGX_MIN_ALPHA);                                                           \
    b.alpha = fmax(alpha, MCL_GGX_MIN_ALPHA);                                                                   \
    b.thickness = thickness;                                                                                    \
    b.maxDepth = maxDepth;                                                                                      \
    b.samples = vsel(samples > 1u, samples, (U)(1u));                                                           \
    return b;                                                                                                   \
  }                                                                                                             \
  MCL_INLINE F3 P##coated_conductor_inside(B b, F3 w) {                                                         \
    F tx = w.x * (1.0f / b.ior), ty = w.y * (1.0f / b.ior);                                                     \
    return V##_make(tx, ty, sqrt(fmax((F)(0.0f), 1.0f - tx * tx - ty * ty)));                                  \
  }                                                                                                             \
  MCL_INLINE F3 P##coated_conductor_base_f(B b, F3 v, F3 w) {                                                   \
    F3 h = V##_normalize(V##_add(v, w));                                                                        \
    F3 fr = P##fresnel_conductor(fmin(fmax(V##_dot(v, h), 0.0f), 1.0f), b.eta, b.k);                           \
    return V##_scale(fr, P##ggx_eval_cos(v, w, b.baseAlpha) / fmax(w.z, 1e-7f));                                \
  }                                                                                                             \
  MCL_INLINE F3 P##coated_conductor_walk(B b, F3 woL, F3 wiL, RO seed, M live) {                                \
    F ct;                                                                                                       \
    F fo = P##fresnel_dielectric(woL.z, b.ior, &ct), fi = P##fresnel_dielectric(wiL.z, b.ior, &ct);            \
    F3 wiIn = P##coated_conductor_inside(b, wiL);                                                               \
    F3 beta = V##_scale(V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f)), (1.0f - fo) / (b.ior * b.ior));             \
    F exitWeight = E##exp_neg(b.thickness / fmax(wiIn.z, 1e-7f)) * (1.0f - fi);                                 \
    F3 f = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                                           \
    F3 v = P##coated_conductor_inside(b, woL); /* toward the viewer's side, seen from the base */              \
    U visits = (b.maxDepth + 1u) / 2u;         /* a visit is two events: the base and the coat */              \
    for (uint k = 0;; ++k) {                                                                                    \
      live = live & (k < visits);                                                                               \
      if (!ANY(live)) break;                                                                                    \
      RO r = PCG(seed.x, seed.y, seed.z, seed.w + k);                                                           \
      F m = fmax(beta.x, fmax(beta.y, beta.z));                                                                 \
      if (k > 1u) { /* Russian roulette */                                                                      \
        F q = fmax((F)(0.0f), 1.0f - m);                                                                        \
        M roulette = live & (m < 0.25f);                                                                        \
        M dies = roulette & (UNIT(r.x) < q);                                                                    \
        live = live & (dies == (M)(0));                                                                         \
        beta = V##_select(roulette & (dies == (M)(0)), V##_scale(beta, 1.0f / (1.0f - q)), beta);               \
      }                                                                                                         \
      beta = V##_select(live, V##_scale(beta, E##exp_neg(b.thickness / fmax(v.z, 1e-7f))), beta); /* down */   \
      f = V##_select(live, V##_add(f, V##_scale(V##_mul(beta, P##coated_conductor_base_f(b, v, wiIn)), exitWeight)), f); \
      F3 h = P##ggx_sample_visible_normal(v, b.baseAlpha, UNIT(r.y), UNIT(r.z));                                \
      F3 u = P##reflect_about(v, h);                                                                            \
      F up = vsel(u.z > 0.0f, (F)(1.0f), (F)(0.0f));                                                            \
      F3 fr = P##fresnel_conductor(fmin(fmax(V##_dot(v, h), 0.0f), 1.0f), b.eta, b.k);                          \
      F3 next = V##_scale(V##_mul(beta, fr), up * P##ggx_g2(v, u, b.baseAlpha) / P##ggx_g1(v, b.baseAlpha));    \
      next = V##_scale(next, E##exp_neg(b.thickness / fmax(u.z, 1e-7f))); /* up to the coat */                 \
      next = V##_scale(next, P##fresnel_dielectric(fmax(u.z, 0.0f), 1.0f / b.ior, &ct));                        \
      beta = V##_select(live, next, beta);                                                                      \
      v = V##_select(live, V##_make(-u.x, -u.y, u.z), v); /* mirrored by the flat underside */                  \
      live = live & (fmax(beta.x, fmax(beta.y, beta.z)) > 0.0f);                                                \
    }                                                                                                           \
    return f;                                                                                                   \
  }                                                                                                             \
  MCL_INLINE F3 P##coated_conductor_eval(B b, FR s, F3 wo, F3 wi) {                                             \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                                \
    M ok = (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);                                        \
    F3 zero = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                                        \
    if (!ANY(ok)) return zero;                                                                                  \
    F3 h = V##_normalize(V##_add(woL, wiL));                                                                    \
    F ct;                                                                                                       \
    F coat = P##fresnel_dielectric(fmax(V##_dot(woL, h), 0.0f), b.ior, &ct) * P##ggx_eval_cos(woL, wiL, b.alpha); \
    RO seed = P##coated_diffuse_seed(wo, wi);                                                                   \
    F3 walk = zero;                                                                                             \
    for (uint k = 0;; ++k) {                                                                                    \
      M more = ok & (k < b.samples);                                                                            \
      if (!ANY(more)) break;                                                                                    \
      walk = V##_select(more, V##_add(walk, P##coated_conductor_walk(b, woL, wiL, seed, more)), walk);         \
      seed.y += 0x9e3779b9u; /* the next walk's numbers */                                                      \
    }                                                                                                           \
    return V##_select(ok, V##_add(V##_make(coat, coat, coat), V##_scale(walk, wiL.z / CVT_F_U(b.samples))), zero); \
  }                                                                                                             \
  MCL_INLINE F3 P##coated_conductor_f(B b, FR s, F3 wo, F3 wi) {                                                \
    return P##over_cosine(P##coated_conductor_eval(b, s, wo, wi), V##_dot(s.ns, wi));                           \
  }                                                                                                             \
  MCL_INLINE F P##coated_conductor_coat_prob(B b, F cosO) {                                                     \
    F ct;                                                                                                       \
    return fmin(fmax(P##fresnel_dielectric(fmax(cosO, 0.0f), b.ior, &ct), 0.1f), 0.9f);                         \
  }                                                                                                             \
  MCL_INLINE F P##coated_conductor_pdf(B b, FR s, F3 wo, F3 wi) {                                               \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                                \
    M ok = (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);                                        \
    F ps = P##coated_conductor_coat_prob(b, woL.z);                                                             \
    F3 woIn = P##coated_conductor_inside(b, woL), wiIn = P##coated_conductor_inside(b, wiL);                    \
    F base = P##ggx_pdf(woIn, wiIn, b.baseAlpha) * wiL.z / (b.ior * b.ior * fmax(wiIn.z, 1e-7f));             \
    F p = ps * P##ggx_pdf(woL, wiL, b.alpha) + (1.0f - ps) * base;                                              \
    return vsel(ok, p, (F)(0.0f));                                                                              \
  }                                                                                                             \
  MCL_INLINE BS P##coated_conductor_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                             \
    F3 woL = P##to_local(wo, s.ns);                                                                             \
    M up = woL.z > 0.0f;                                                                                        \
    M coatLobe = uLobe < P##coated_conductor_coat_prob(b, woL.z);                                               \
    F3 v = V##_select(coatLobe, woL, P##coated_conductor_inside(b, woL));                                      \
    F3 h = V##_select(up, P##ggx_sample_visible_normal(v, vsel(coatLobe, b.alpha, b.baseAlpha), u1, u2),        \
                      V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f)));                                               \
    F3 w = P##reflect_about(v, h);                                                                              \
    /* The base lobe's reflection refracted out: tangent x ior; none under total internal reflection. */       \
    F s2 = (w.x * w.x + w.y * w.y) * (b.ior * b.ior);                                                           \
    F3 out = V##_make(w.x * b.ior, w.y * b.ior, sqrt(fmax((F)(0.0f), 1.0f - s2)));                              \
    M valid = coatLobe | ((w.z > 0.0f) & (s2 < 1.0f));                                                          \
    BS r;                                                                                                       \
    r.wi = P##to_world(V##_select(coatLobe, w, out), s.ns);                                                     \
    F pdf = P##coated_conductor_pdf(b, s, wo, r.wi);                                                            \
    M ok = up & valid & (pdf > 0.0f);                                                                           \
    r.pdf = vsel(ok, pdf, (F)(0.0f));                                                                           \
    r.weight = V##_select(ok, V##_scale(P##coated_conductor_eval(b, s, wo, r.wi), 1.0f / fmax(pdf, 1e-30f)),    \
                          V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                           \
    r.flags = (M)(0);                                                                                           \
    return r;                                                                                                   \
  }
MCL_DEFINE_COATED_CONDUCTOR(, float, float3, int, uint, f3, MCL_ANY1, CoatedConductorBsdf, SurfaceFrame, BsdfSample,
                            RngOut, pcg4d, u32_to_unit, (float), mcl_)

MCL_INLINE CoatedConductorBsdf coated_conductor_from_material(Material m, float3 albedo) {
  (void)albedo;
  return coated_conductor_make(xyz(m.params0), xyz(m.params1), m.params0.w, m.params1.w, m.specular.x, m.specular.y,
                               as_uint(m.specular.z), as_uint(m.specular.w));
}

MCL_INLINE int coated_conductor_is_delta(CoatedConductorBsdf b) {
  (void)b;
  return 0;
}


// Written once for floats and lanes (lane_bsdf.h): coated_conductor_albedo, the albedo AOV: the base metal's reflectance at normal incidence under the coat;
// coated_conductor_direction_weight: eval / pdf, counted where pdf > 0.
#define MCL_DEFINE_COATED_CONDUCTOR_WEIGHTS(P, F, F3, M, V, B, FR)                                      \
  MCL_INLINE F3 P##coated_conductor_albedo(B b) {                                                       \
    return P##fresnel_conductor((F)(1.0f), b.eta, b.k);                                                 \
  }                                                                                                     \
  MCL_INLINE F3 P##coated_conductor_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {       \
    *counts = pdf > 0.0f;                                                                               \
    return V##_scale(P##coated_conductor_eval(b, s, wo, wi), 1.0f / fmax(pdf, 1e-30f));                 \
  }
MCL_DEFINE_COATED_CONDUCTOR_WEIGHTS(, float, float3, int, f3, CoatedConductorBsdf, SurfaceFrame)
