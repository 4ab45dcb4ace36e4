// bsdf_coated_diffuse.h: the material kind "coated_diffuse" (material_kinds.h): a dielectric coat
// of index ior over a Lambertian base of reflectance `albedo` (Kd x albedo texture), a clear layer
// of some thickness between them; pbrt-v4's layered model (its LayeredBxDF with a dielectric top
// and a diffuse bottom), evaluated stochastically. Reads a Material's params0 (x: the coat's GGX
// alpha, y: ior, z: thickness) and params1 (x: the walk's bounce limit, y: walks per evaluation,
// both as uint bits). Pure; compiled by the kernels and the host tests.
//
// f = the coat's own reflection (GGX of alpha at least MCL_GGX_MIN_ALPHA, times the dielectric
// Fresnel of wo.h: a smooth coat is that near-mirror lobe, so the kind has no delta lobe and every
// integrator's MIS applies) + light that crosses the coat, walks between the base and the coat's
// underside and crosses out again. That second part is estimated by a random walk, as pbrt-v4
// does: it enters along wo (radiance through the interface scaled by T(wo) / ior^2, T = 1 - F),
// and at every visit of the base adds the path out toward wi (Lambert R / pi, the layer's
// transmittance, T(wi)); the base reflects cosine-weighted (weight R), the coat's underside
// reflects by its Fresnel F (total internal reflection: 1); each crossing of the layer is
// attenuated by exp(-thickness / |cos|) (pbrt's unit extinction); Russian roulette after 3
// events once the throughput is below 1/4. The interface is flat for the light inside the layer
// (the refraction of a rough coat is taken as smooth: the coat's roughness shapes only its own
// reflection), so the walk needs only cosines. No scattering medium in the layer (pbrt's albedo,
// g: the loaders warn).
//
// The walk's numbers are a hash (pcg4d) of the bits of wo and wi: the estimate is a fixed
// function of the directions, so it is the same on every device, lane width and wave size (the
// interface hands eval no sampler dimensions; sample's direction comes from u1, u2, uLobe).
// Sampling: the coat's GGX lobe (visible normals) with probability ps = F(wo) against the
// base's cosine lobe, clamped to [0.1, 0.9]; pdf is that exact mixture, and the sample's weight is
// eval / pdf with eval's estimate, unbiased because eval is.
#pragma once
#include "bsdf_common.h"
#include "exp_neg.h"
#include "microfacet.h"
#include "rng.h"

#define MCL_DEFINE_COATED_DIFFUSE_TYPE(B, F, F3, U)                     \
  typedef struct {                                                       \
    F3 base;     /* Lambertian reflectance of the base at the hit */     \
    F alpha;     /* the coat's GGX alpha */                              \
    F eta;       /* the coat's index (inside / outside) */               \
    F thickness; /* of the clear layer */                                \
    U maxDepth;  /* scattering events per walk */                        \
    U samples;   /* walks per evaluation */                              \
  } B;
MCL_DEFINE_COATED_DIFFUSE_TYPE(CoatedDiffuseBsdf, float, float3, uint)

MCL_INLINE CoatedDiffuseBsdf coated_diffuse_from_material(Material m, float3 albedo) {
  CoatedDiffuseBsdf b;
  b.base = albedo;
  b.alpha = fmax(m.params0.x, MCL_GGX_MIN_ALPHA);
  b.eta = m.params0.y;
  b.thickness = m.params0.z;
  b.maxDepth = as_uint(m.params1.x);
  b.samples = as_uint(m.params1.y) > 1u ? as_uint(m.params1.y) : 1u;
  return b;
}

MCL_INLINE int coated_diffuse_is_delta(CoatedDiffuseBsdf b) {
  (void)b;
  return 0;
}


// The kind's functions written once for floats and lanes (P, F, F3, M, U, V, ANY: the prefix,
// float, float3, int mask, uint, f3, MCL_ANY1 here; the packet stages' v_, vfloat, vfloat3, vmask,
// vuint, v3, v_any in stages/lane_bsdf.h, with the frame FR, sample type BS, random-number type RO,
// pcg4d PCG, u32_to_unit UNIT, the float -> uint bit cast AS_U, uint -> float CVT_F_U and exp_neg's
// prefix E). A lane's walk stops (its mask clears) where the scalar walk breaks; the walks run
// while some lane's does.
// - coated_fresnel_out, coated_cos_inside: the Fresnel reflectance from outside at cos c (> 0), and
//   the cosine inside the coat.
// - coated_diffuse_walk: one walk's estimate of the through-the-coat part of f (no cosine) for
//   local cosines cosO, cosI (> 0) with numbers from pcg4d(seed, step), in the lanes of `live`.
// - coated_diffuse_seed: the walk's seed from the directions' bits (wo first: the estimate is
//   reciprocal in expectation).
// - coated_diffuse_eval, _f, _pdf, _sample: f cos (the coat's GGX reflection plus the walks'
//   mean), f, the mixture pdf of the coat's lobe and the cosine lobe, a direction with weight
//   eval / pdf.
#define MCL_DEFINE_COATED_DIFFUSE(P, F, F3, M, U, V, ANY, B, FR, BS, RO, PCG, UNIT, AS_U, CVT_F_U, E)          \
  MCL_INLINE F P##coated_fresnel_out(B b, F c) {                                                            \
    F ct;                                                                                                   \
    return P##fresnel_dielectric(c, b.eta, &ct);                                                            \
  }                                                                                                         \
  MCL_INLINE F P##coated_cos_inside(B b, F c) {                                                             \
    F ct;                                                                                                   \
    P##fresnel_dielectric(c, b.eta, &ct);                                                                   \
    return ct;                                                                                              \
  }                                                                                                         \
  MCL_INLINE F3 P##coated_diffuse_walk(B b, F cosO, F cosI, RO seed, M live) {                              \
    F fo = P##coated_fresnel_out(b, cosO), fi = P##coated_fresnel_out(b, cosI);                             \
    F co = P##coated_cos_inside(b, cosO), ci = P##coated_cos_inside(b, cosI);                               \
    F3 beta = V##_scale(V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f)), (1.0f - fo) / (b.eta * b.eta));          \
    F3 exitWeight = V##_scale(b.base, MCL_INV_PI * E##exp_neg(b.thickness / ci) * (1.0f - fi));             \
    F3 f = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                                       \
    F c = co;            /* cosine of the walk's direction inside the layer */                              \
    M atBase = (M)(0);   /* the walk starts just under the coat, heading down */                            \
    for (uint depth = 0;; ++depth) {                                                                        \
      live = live & (depth < b.maxDepth);                                                                   \
      if (!ANY(live)) break;                                                                                \
      RO r = PCG(seed.x, seed.y, seed.z, seed.w + depth);                                                   \
      if (depth > 3u) { /* Russian roulette */                                                              \
        F m = fmax(beta.x, fmax(beta.y, beta.z));                                                           \
        F q = fmax((F)(0.0f), 1.0f - m);                                                                    \
        M roulette = live & (m < 0.25f);                                                                    \
        M dies = roulette & (UNIT(r.x) < q);                                                                \
        live = live & (dies == (M)(0));                                                                     \
        beta = V##_select(roulette & (dies == (M)(0)), V##_scale(beta, 1.0f / (1.0f - q)), beta);           \
      }                                                                                                     \
      beta = V##_select(live, V##_scale(beta, E##exp_neg(b.thickness / c)), beta);                          \
      atBase = vsel(live, atBase == (M)(0), atBase);                                                        \
      M base = live & atBase;                                                                               \
      f = V##_select(base, V##_add(f, V##_mul(beta, exitWeight)), f);                                       \
      F ct;                                                                                                 \
      F fr = P##fresnel_dielectric(c, 1.0f / b.eta, &ct);                                                   \
      beta = V##_select(live, V##_select(atBase, V##_mul(beta, b.base), V##_scale(beta, fr)), beta);        \
      c = vsel(base, sqrt(fmax(UNIT(r.y), 1e-7f)), c); /* cosine-weighted: cos = sqrt(u) */                  \
      live = live & (fmax(beta.x, fmax(beta.y, beta.z)) > 0.0f);                                            \
    }                                                                                                       \
    return f;                                                                                               \
  }                                                                                                         \
  MCL_INLINE RO P##coated_diffuse_seed(F3 wo, F3 wi) {                                                      \
    return PCG(AS_U(wo.x) ^ AS_U(wi.z), AS_U(wo.y), AS_U(wi.x) ^ AS_U(wo.z), AS_U(wi.y));                   \
  }                                                                                                         \
  MCL_INLINE F3 P##coated_diffuse_eval(B b, FR s, F3 wo, F3 wi) {                                           \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                            \
    M ok = (V##_dot(s.ng, wi) > 0.0f) & (woL.z > 0.0f) & (wiL.z > 0.0f);                                    \
    F3 zero = V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f));                                                    \
    if (!ANY(ok)) return zero;                                                                              \
    F3 h = V##_normalize(V##_add(woL, wiL));                                                                \
    F coat = P##coated_fresnel_out(b, fmax(V##_dot(woL, h), 0.0f)) * P##ggx_eval_cos(woL, wiL, b.alpha);    \
    RO seed = P##coated_diffuse_seed(wo, wi);                                                               \
    F3 walk = zero;                                                                                         \
    for (uint k = 0;; ++k) {                                                                                \
      M more = ok & (k < b.samples);                                                                        \
      if (!ANY(more)) break;                                                                                \
      walk = V##_select(more, V##_add(walk, P##coated_diffuse_walk(b, woL.z, wiL.z, seed, more)), walk);    \
      seed.y += 0x9e3779b9u; /* the next walk's numbers */                                                  \
    }                                                                                                       \
    return V##_select(ok, V##_add(V##_make(coat, coat, coat), V##_scale(walk, wiL.z / CVT_F_U(b.samples))), zero); \
  }                                                                                                         \
  MCL_INLINE F3 P##coated_diffuse_f(B b, FR s, F3 wo, F3 wi) {                                              \
    return P##over_cosine(P##coated_diffuse_eval(b, s, wo, wi), V##_dot(s.ns, wi));                         \
  }                                                                                                         \
  MCL_INLINE F P##coated_diffuse_coat_prob(B b, F cosO) {                                                   \
    return fmin(fmax(P##coated_fresnel_out(b, fmax(cosO, 0.0f)), 0.1f), 0.9f);                              \
  }                                                                                                         \
  MCL_INLINE F P##coated_diffuse_pdf(B b, FR s, F3 wo, F3 wi) {                                             \
    F3 woL = P##to_local(wo, s.ns), wiL = P##to_local(wi, s.ns);                                            \
    return P##ggx_cosine_mix_pdf(woL, wiL, V##_dot(s.ng, wi) > 0.0f, P##coated_diffuse_coat_prob(b, woL.z), b.alpha); \
  }                                                                                                         \
  MCL_INLINE BS P##coated_diffuse_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                           \
    F3 woL = P##to_local(wo, s.ns);                                                                         \
    M up = woL.z > 0.0f;                                                                                    \
    F3 wiL = P##ggx_cosine_mix_sample(woL, uLobe < P##coated_diffuse_coat_prob(b, woL.z), b.alpha, u1, u2); \
    BS r;                                                                                                   \
    r.wi = P##to_world(wiL, s.ns);                                                                          \
    F pdf = P##coated_diffuse_pdf(b, s, wo, r.wi);                                                          \
    M ok = up & (pdf > 0.0f);                                                                               \
    r.pdf = vsel(ok, pdf, (F)(0.0f));                                                                       \
    r.weight = V##_select(ok, V##_scale(P##coated_diffuse_eval(b, s, wo, r.wi), 1.0f / fmax(pdf, 1e-30f)),  \
                          V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                       \
    r.flags = (M)(0);                                                                                       \
    return r;                                                                                               \
  }
MCL_DEFINE_COATED_DIFFUSE(, float, float3, int, uint, f3, MCL_ANY1, CoatedDiffuseBsdf, SurfaceFrame, BsdfSample, RngOut,
                          pcg4d, u32_to_unit, as_uint, (float), mcl_)

// Written once for floats and lanes (lane_bsdf.h): coated_diffuse_albedo, the albedo AOV: the base's colour (what a denoiser should see under a clear coat);
// coated_diffuse_direction_weight: eval / pdf, counted where pdf > 0.
#define MCL_DEFINE_COATED_DIFFUSE_WEIGHTS(P, F, F3, M, V, B, FR)                                        \
  MCL_INLINE F3 P##coated_diffuse_albedo(B b) {                                                         \
    return b.base;                                                                                      \
  }                                                                                                     \
  MCL_INLINE F3 P##coated_diffuse_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {         \
    *counts = pdf > 0.0f;                                                                               \
    return V##_scale(P##coated_diffuse_eval(b, s, wo, wi), 1.0f / fmax(pdf, 1e-30f));                   \
  }
MCL_DEFINE_COATED_DIFFUSE_WEIGHTS(, float, float3, int, f3, CoatedDiffuseBsdf, SurfaceFrame)
