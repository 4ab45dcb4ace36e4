// light_environment.h: the light kind "environment" (light_kinds.h): radiance from infinitely far
// away (shared/environment.h: the constant or the map, its importance sampling). Reads FrameParams
// and the environment's map and CDF tables; pure; compiled by the kernels and the host.
#pragma once
#include "environment.h"
#include "light_scene.h"

// Its share of the lights' power (all samples without other lights), none without an environment.
MCL_INLINE float environment_light_probability(MCL_CONSTANT const FrameParams* f) { return env_pick_probability(f); }

// A direction by the map's luminance (u1, u2; u0 unused); pdf per solid angle within the kind.
MCL_INLINE LightSample environment_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin,
                                                float u0, float u1, float u2) {
  (void)origin;
  (void)u0;
  EnvSample es = env_sample(f, ls.envMap, ls.envCdf, u1, u2);
  LightSample s = no_light_sample();
  s.wi = es.wi;
  s.le = es.le;
  s.pdf = es.pdf;
  return s;
}

// Pdf within the kind of direction hit.wi (0 without an environment).
MCL_INLINE float environment_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  return env_pick_probability(f) > 0.0f ? env_pdf(f, ls.envMap, hit.wi) : 0.0f;
}

// Radiance arriving along -hit.wi (0 without an environment).
MCL_INLINE float3 environment_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  return env_present(f) ? env_radiance(f, ls.envMap, hit.wi) : make_float3(0.0f, 0.0f, 0.0f);
}
