// light_directional.h: the light kind "directional" (light_kinds.h): light from infinitely far
// away in one direction, irradiance E (W/m^2) on a surface facing it; a delta light (next-event
// estimation only). Reads FrameParams and the light records; pure; compiled by the kernels and the
// host.
#pragma once
#include "light_records.h"

MCL_INLINE float directional_light_probability(MCL_CONSTANT const FrameParams* f) { return f->shareDirectional; }

// The sample of the directional light travelling along `direction` with irradiance E, picked with
// probability `pick`: wi against its direction, Le-like factor E, pdf = pick, unbounded shadow ray.
// Written once for floats and lanes (the parameters of MCL_DEFINE_DELTA_LIGHT_SAMPLE).
#define MCL_DEFINE_DIRECTIONAL_LIGHT(P, F, F3, M, V, LS)                                   \
  MCL_INLINE LS P##directional_light_at(F3 direction, F3 irradiance, F pick) {             \
    return P##delta_light_sample(V##_scale(direction, -1.0f), irradiance, pick, (F)(INFINITY), \
                                 (F)(0.0f) == (F)(0.0f)); /* always */                    \
  }
MCL_DEFINE_DIRECTIONAL_LIGHT(, float, float3, int, f3, LightSample)

// A directional light by power (u0): directional_light_at the picked record.
MCL_INLINE LightSample directional_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin,
                                                float u0, float u1, float u2) {
  (void)origin;
  (void)u1;
  (void)u2;
  MCL_GLOBAL const LightRecord* r =
      &ls.records[pick_light_record(ls.records, f->directionalFirst, f->directionalCount, u0)];
  return directional_light_at(xyz(r->direction), xyz(r->intensity), r->direction.w);
}

// Delta: a BSDF ray never reaches it.
MCL_INLINE float directional_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return 0.0f;
}

MCL_INLINE float3 directional_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return make_float3(0.0f, 0.0f, 0.0f);
}
