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

typedef struct {
  float3 base;      // Lambertian reflectance of the base at the hit
  float alpha;      // the coat's GGX alpha
  float eta;        // the coat's index (inside / outside)
  float thickness;  // of the clear layer
  uint maxDepth;    // scattering events per walk
  uint samples;     // walks per evaluation
} CoatedDiffuseBsdf;

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

// The albedo AOV: the base's colour (what a denoiser should see under a clear coat).
MCL_INLINE float3 coated_diffuse_albedo(CoatedDiffuseBsdf b) { return b.base; }

// Fresnel reflectance from outside at cos c (> 0), and from inside the coat.
MCL_INLINE float coated_fresnel_out(CoatedDiffuseBsdf b, float c) {
  float ct;
  return fresnel_dielectric(c, b.eta, &ct);
}
MCL_INLINE float coated_cos_inside(CoatedDiffuseBsdf b, float c) {
  float ct;
  fresnel_dielectric(c, b.eta, &ct);
  return ct;
}

// One walk's estimate of the through-the-coat part of f (no cosine) for local cosines cosO,
// cosI (> 0) with numbers from pcg4d(seed, step): the walk of the header.
MCL_INLINE float3 coated_diffuse_walk(CoatedDiffuseBsdf b, float cosO, float cosI, RngOut seed) {
  float fo = coated_fresnel_out(b, cosO), fi = coated_fresnel_out(b, cosI);
  float co = coated_cos_inside(b, cosO), ci = coated_cos_inside(b, cosI);
  float3 beta = make_float3(1.0f, 1.0f, 1.0f) * ((1.0f - fo) / (b.eta * b.eta));
  float3 exitWeight = b.base * (MCL_INV_PI * mcl_exp_neg(b.thickness / ci) * (1.0f - fi));
  float3 f = make_float3(0.0f, 0.0f, 0.0f);
  float c = co;       // cosine of the walk's direction inside the layer
  int atBase = 0;     // the walk starts just under the coat, heading down
  for (uint depth = 0; depth < b.maxDepth; ++depth) {
    RngOut r = pcg4d(seed.x, seed.y, seed.z, seed.w + depth);
    float m = fmax(beta.x, fmax(beta.y, beta.z));
    if (depth > 3u && m < 0.25f) {
      float q = fmax(0.0f, 1.0f - m);
      if (u32_to_unit(r.x) < q) break;
      beta = beta * (1.0f / (1.0f - q));
    }
    beta = beta * mcl_exp_neg(b.thickness / c);
    atBase = !atBase;
    if (atBase) {
      f = f + beta * exitWeight;
      beta = beta * b.base;
      c = sqrt(fmax(u32_to_unit(r.y), 1e-7f));  // cosine-weighted: cos = sqrt(u)
    } else {
      float ct;
      beta = beta * fresnel_dielectric(c, 1.0f / b.eta, &ct);
    }
    if (!(fmax(beta.x, fmax(beta.y, beta.z)) > 0.0f)) break;
  }
  return f;
}

// The walk's seed from the directions' bits (wo first: the estimate is reciprocal in expectation).
MCL_INLINE RngOut coated_diffuse_seed(float3 wo, float3 wi) {
  return pcg4d(as_uint(wo.x) ^ as_uint(wi.z), as_uint(wo.y), as_uint(wi.x) ^ as_uint(wo.z), as_uint(wi.y));
}

MCL_INLINE float3 coated_diffuse_eval(CoatedDiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  int ok = above_surface(s.ng, wi) && woL.z > 0.0f && wiL.z > 0.0f;
  if (!ok) return make_float3(0.0f, 0.0f, 0.0f);
  float3 h = normalize(woL + wiL);
  float coat = coated_fresnel_out(b, fmax(dot(woL, h), 0.0f)) * ggx_eval_cos(woL, wiL, b.alpha);
  RngOut seed = coated_diffuse_seed(wo, wi);
  float3 walk = make_float3(0.0f, 0.0f, 0.0f);
  for (uint k = 0; k < b.samples; ++k) {
    walk = walk + coated_diffuse_walk(b, woL.z, wiL.z, seed);
    seed.y += 0x9e3779b9u;  // the next walk's numbers
  }
  return make_float3(coat, coat, coat) + walk * (wiL.z / (float)b.samples);
}

MCL_INLINE float3 coated_diffuse_f(CoatedDiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float c = dot(s.ns, wi);
  return c > 0.0f ? coated_diffuse_eval(b, s, wo, wi) * (1.0f / c) : make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float coated_diffuse_coat_prob(CoatedDiffuseBsdf b, float cosO) {
  return fmin(fmax(coated_fresnel_out(b, fmax(cosO, 0.0f)), 0.1f), 0.9f);
}

MCL_INLINE float coated_diffuse_pdf(CoatedDiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  return ggx_cosine_mix_pdf(woL, wiL, above_surface(s.ng, wi), coated_diffuse_coat_prob(b, woL.z), b.alpha);
}

MCL_INLINE BsdfSample coated_diffuse_sample(CoatedDiffuseBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                            float uLobe) {
  float3 woL = to_local(wo, s.ns);
  int up = woL.z > 0.0f;
  float3 wiL = ggx_cosine_mix_sample(woL, uLobe < coated_diffuse_coat_prob(b, woL.z), b.alpha, u1, u2);
  BsdfSample r;
  r.wi = to_world(wiL, s.ns);
  float pdf = coated_diffuse_pdf(b, s, wo, r.wi);
  int ok = up && pdf > 0.0f;
  r.pdf = ok ? pdf : 0.0f;
  r.weight = ok ? coated_diffuse_eval(b, s, wo, r.wi) * (1.0f / fmax(pdf, 1e-30f)) : make_float3(0.0f, 0.0f, 0.0f);
  r.flags = 0;
  return r;
}

MCL_INLINE BsdfDirection coated_diffuse_sample_direction(CoatedDiffuseBsdf b, SurfaceFrame s, float3 wo, float u1,
                                                         float u2, float uLobe) {
  return bsdf_direction_of(coated_diffuse_sample(b, s, wo, u1, u2, uLobe));
}

MCL_INLINE BsdfWeight coated_diffuse_direction_weight(CoatedDiffuseBsdf b, SurfaceFrame s, float3 wo, float3 wi,
                                                      float pdf) {
  BsdfWeight w;
  w.counts = pdf > 0.0f;
  w.weight = coated_diffuse_eval(b, s, wo, wi) * (1.0f / fmax(pdf, 1e-30f));
  return w;
}
