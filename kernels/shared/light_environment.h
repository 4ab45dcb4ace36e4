// light_environment.h: the light kind "environment" (light_kinds.h): radiance from infinitely far
// away (shared/environment.h: the constant or the map, its importance sampling). Reads FrameParams
// and the environment's map and CDF tables; pure; compiled by the kernels and the host.
#pragma once
#include "environment.h"
#include "light_scene.h"

// Its share of the lights' power (all samples without other lights), none without an environment.
MCL_INLINE float environment_light_probability(MCL_CONSTANT const FrameParams* f) { return env_pick_probability(f); }

// The kind's sample, pdf and radiance by direction, written once for floats and lanes (P, F, F3,
// M, LS, ES: the prefix, float, float3, int, LightSample, EnvSample here; the lanes' types in
// stages/lane_lights.h). The pdf is the light
// pdf's environment term, selection included.
#define MCL_DEFINE_ENVIRONMENT_LIGHT(P, F, F3, M, LS, ES, V)                                                  \
  /* A direction by the map's luminance (u1, u2); pdf per solid angle within the kind. */               \
  MCL_INLINE LS P##environment_light_at(MCL_CONSTANT const FrameParams* f, LightScene ls, F u1, F u2) {   \
    ES es = P##env_sample(f, ls.envMap, ls.envCdf, u1, u2);                                     \
    LS s;                                                                                                 \
    s.wi = es.wi;                                                                                         \
    s.le = es.le;                                                                                         \
    s.pdf = es.pdf;                                                                                       \
    s.tmax = (F)(INFINITY);                                                                               \
    s.delta = (M)(0);                                                                                     \
    return s;                                                                                             \
  }                                                                                                       \
  /* Light-sampling pdf of direction wi, the kind's share included (0 without an environment). */        \
  MCL_INLINE F P##environment_light_pdf_of(MCL_CONSTANT const FrameParams* f, LightScene ls, F3 wi) {    \
    float share = environment_light_probability(f);                                                       \
    return share * (share > 0.0f ? P##env_pdf(f, ls.envMap, wi) : (F)(0.0f));                             \
  }                                                                                                       \
  /* Radiance arriving along -wi (0 without an environment). */                                           \
  MCL_INLINE F3 P##environment_light_eval_of(MCL_CONSTANT const FrameParams* f, LightScene ls, F3 wi) {  \
    return env_present(f) ? P##env_radiance(f, ls.envMap, wi) : V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)); \
  }
MCL_DEFINE_ENVIRONMENT_LIGHT(, float, float3, int, LightSample, EnvSample, f3)

MCL_INLINE LightSample environment_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin,
                                                float u0, float u1, float u2) {
  (void)origin;
  (void)u0;
  return environment_light_at(f, ls, u1, u2);
}

// Pdf within the kind of direction hit.wi (0 without an environment).
MCL_INLINE float environment_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  return env_pick_probability(f) > 0.0f ? env_pdf(f, ls.envMap, hit.wi) : 0.0f;
}

// Radiance arriving along -hit.wi (0 without an environment).
MCL_INLINE float3 environment_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  return environment_light_eval_of(f, ls, hit.wi);
}
