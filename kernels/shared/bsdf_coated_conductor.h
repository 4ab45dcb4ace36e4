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

typedef struct {
  float3 eta, k;      // the metal's index relative to the coat
  float baseAlpha;    // the base's GGX alpha (at least MCL_GGX_MIN_ALPHA)
  float alpha;        // the coat's GGX alpha
  float ior;          // the coat's index (inside / outside)
  float thickness;    // of the clear layer
  uint maxDepth;      // scattering events per walk
  uint samples;       // walks per evaluation
} CoatedConductorBsdf;

MCL_INLINE CoatedConductorBsdf coated_conductor_from_material(Material m, float3 albedo) {
  (void)albedo;
  CoatedConductorBsdf b;
  b.ior = m.specular.x;
  b.eta = xyz(m.params0) * (1.0f / b.ior);
  b.k = xyz(m.params1) * (1.0f / b.ior);
  b.baseAlpha = fmax(m.params0.w, MCL_GGX_MIN_ALPHA);
  b.alpha = fmax(m.params1.w, MCL_GGX_MIN_ALPHA);
  b.thickness = m.specular.y;
  b.maxDepth = as_uint(m.specular.z);
  b.samples = as_uint(m.specular.w) > 1u ? as_uint(m.specular.w) : 1u;
  return b;
}

MCL_INLINE int coated_conductor_is_delta(CoatedConductorBsdf b) {
  (void)b;
  return 0;
}

// The albedo AOV: the base metal's reflectance at normal incidence under the coat.
MCL_INLINE float3 coated_conductor_albedo(CoatedConductorBsdf b) { return fresnel_conductor(1.0f, b.eta, b.k); }

// A local direction w (w.z > 0) outside as the layer sees it: (w.xy / ior, cos of the refraction).
MCL_INLINE float3 coated_conductor_inside(CoatedConductorBsdf b, float3 w) {
  float3 t = make_float3(w.x, w.y, 0.0f) * (1.0f / b.ior);
  return make_float3(t.x, t.y, sqrt(fmax(0.0f, 1.0f - t.x * t.x - t.y * t.y)));
}

// The base's GGX conductor f (no cosine) between two inside directions above it.
MCL_INLINE float3 coated_conductor_base_f(CoatedConductorBsdf b, float3 v, float3 w) {
  float3 h = normalize(v + w);
  float3 fr = fresnel_conductor(fmin(fmax(dot(v, h), 0.0f), 1.0f), b.eta, b.k);
  return fr * (ggx_eval_cos(v, w, b.baseAlpha) / fmax(w.z, 1e-7f));
}

// One walk's estimate of the through-the-coat part of f (no cosine) for local directions wo, wi
// (z > 0) with numbers from pcg4d(seed, step): the walk of the header.
MCL_INLINE float3 coated_conductor_walk(CoatedConductorBsdf b, float3 woL, float3 wiL, RngOut seed) {
  float ct;
  float fo = fresnel_dielectric(woL.z, b.ior, &ct), fi = fresnel_dielectric(wiL.z, b.ior, &ct);
  float3 wiIn = coated_conductor_inside(b, wiL);
  float3 beta = make_float3(1.0f, 1.0f, 1.0f) * ((1.0f - fo) / (b.ior * b.ior));
  float exitWeight = mcl_exp_neg(b.thickness / fmax(wiIn.z, 1e-7f)) * (1.0f - fi);
  float3 f = make_float3(0.0f, 0.0f, 0.0f);
  float3 v = coated_conductor_inside(b, woL);  // toward the viewer's side, seen from the base
  uint visits = (b.maxDepth + 1u) / 2u;        // a visit is two events: the base and the coat
  for (uint k = 0; k < visits; ++k) {
    RngOut r = pcg4d(seed.x, seed.y, seed.z, seed.w + k);
    float m = fmax(beta.x, fmax(beta.y, beta.z));
    if (k > 1u && m < 0.25f) {
      float q = fmax(0.0f, 1.0f - m);
      if (u32_to_unit(r.x) < q) break;
      beta = beta * (1.0f / (1.0f - q));
    }
    beta = beta * mcl_exp_neg(b.thickness / fmax(v.z, 1e-7f));  // down to the base
    f = f + beta * coated_conductor_base_f(b, v, wiIn) * exitWeight;
    float3 h = ggx_sample_visible_normal(v, b.baseAlpha, u32_to_unit(r.y), u32_to_unit(r.z));
    float3 u = reflect_about(v, h);
    float up = u.z > 0.0f ? 1.0f : 0.0f;
    float3 fr = fresnel_conductor(fmin(fmax(dot(v, h), 0.0f), 1.0f), b.eta, b.k);
    beta = beta * fr * (up * ggx_g2(v, u, b.baseAlpha) / ggx_g1(v, b.baseAlpha));
    beta = beta * mcl_exp_neg(b.thickness / fmax(u.z, 1e-7f));  // up to the coat
    beta = beta * fresnel_dielectric(fmax(u.z, 0.0f), 1.0f / b.ior, &ct);
    v = make_float3(-u.x, -u.y, u.z);  // mirrored by the flat underside, seen from the base again
    if (!(fmax(beta.x, fmax(beta.y, beta.z)) > 0.0f)) break;
  }
  return f;
}

MCL_INLINE float3 coated_conductor_eval(CoatedConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  int ok = above_surface(s.ng, wi) && woL.z > 0.0f && wiL.z > 0.0f;
  if (!ok) return make_float3(0.0f, 0.0f, 0.0f);
  float3 h = normalize(woL + wiL);
  float ct;
  float coat = fresnel_dielectric(fmax(dot(woL, h), 0.0f), b.ior, &ct) * ggx_eval_cos(woL, wiL, b.alpha);
  RngOut seed = coated_diffuse_seed(wo, wi);
  float3 walk = make_float3(0.0f, 0.0f, 0.0f);
  for (uint k = 0; k < b.samples; ++k) {
    walk = walk + coated_conductor_walk(b, woL, wiL, seed);
    seed.y += 0x9e3779b9u;  // the next walk's numbers
  }
  return make_float3(coat, coat, coat) + walk * (wiL.z / (float)b.samples);
}

MCL_INLINE float3 coated_conductor_f(CoatedConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float c = dot(s.ns, wi);
  return c > 0.0f ? coated_conductor_eval(b, s, wo, wi) * (1.0f / c) : make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float coated_conductor_coat_prob(CoatedConductorBsdf b, float cosO) {
  float ct;
  return fmin(fmax(fresnel_dielectric(fmax(cosO, 0.0f), b.ior, &ct), 0.1f), 0.9f);
}

MCL_INLINE float coated_conductor_pdf(CoatedConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  float3 woL = to_local(wo, s.ns), wiL = to_local(wi, s.ns);
  int ok = above_surface(s.ng, wi) && woL.z > 0.0f && wiL.z > 0.0f;
  float ps = coated_conductor_coat_prob(b, woL.z);
  float3 woIn = coated_conductor_inside(b, woL), wiIn = coated_conductor_inside(b, wiL);
  float base = ggx_pdf(woIn, wiIn, b.baseAlpha) * wiL.z / (b.ior * b.ior * fmax(wiIn.z, 1e-7f));
  float p = ps * ggx_pdf(woL, wiL, b.alpha) + (1.0f - ps) * base;
  return ok ? p : 0.0f;
}

MCL_INLINE BsdfSample coated_conductor_sample(CoatedConductorBsdf b, SurfaceFrame s, float3 wo, float u1, float u2,
                                              float uLobe) {
  float3 woL = to_local(wo, s.ns);
  int up = woL.z > 0.0f;
  int coatLobe = uLobe < coated_conductor_coat_prob(b, woL.z);
  float3 woIn = coated_conductor_inside(b, woL);
  float3 v = coatLobe ? woL : woIn;
  float3 h = up ? ggx_sample_visible_normal(v, coatLobe ? b.alpha : b.baseAlpha, u1, u2) : make_float3(0.0f, 0.0f, 1.0f);
  float3 w = reflect_about(v, h);
  // The base lobe's reflection refracted out: tangent x ior; none under total internal reflection.
  float s2 = (w.x * w.x + w.y * w.y) * (b.ior * b.ior);
  float3 out = make_float3(w.x * b.ior, w.y * b.ior, sqrt(fmax(0.0f, 1.0f - s2)));
  int valid = coatLobe ? 1 : (w.z > 0.0f && s2 < 1.0f);
  float3 wiL = coatLobe ? w : out;
  BsdfSample r;
  r.wi = to_world(wiL, s.ns);
  float pdf = coated_conductor_pdf(b, s, wo, r.wi);
  int ok = up && valid && pdf > 0.0f;
  r.pdf = ok ? pdf : 0.0f;
  r.weight = ok ? coated_conductor_eval(b, s, wo, r.wi) * (1.0f / fmax(pdf, 1e-30f)) : make_float3(0.0f, 0.0f, 0.0f);
  r.flags = 0;
  return r;
}

MCL_INLINE BsdfDirection coated_conductor_sample_direction(CoatedConductorBsdf b, SurfaceFrame s, float3 wo, float u1,
                                                           float u2, float uLobe) {
  return bsdf_direction_of(coated_conductor_sample(b, s, wo, u1, u2, uLobe));
}

MCL_INLINE BsdfWeight coated_conductor_direction_weight(CoatedConductorBsdf b, SurfaceFrame s, float3 wo, float3 wi,
                                                        float pdf) {
  BsdfWeight w;
  w.counts = pdf > 0.0f;
  w.weight = coated_conductor_eval(b, s, wo, wi) * (1.0f / fmax(pdf, 1e-30f));
  return w;
}
