// light_directional.h: the light kind "directional" (light_kinds.h): light from infinitely far
// away in one direction, irradiance E (W/m^2) on a surface facing it; a delta light (next-event
// estimation only). Reads FrameParams and the light records; pure; compiled by the kernels and the
// host.
#pragma once
#include "light_records.h"

MCL_INLINE float directional_light_probability(MCL_CONSTANT const FrameParams* f) { return f->shareDirectional; }

// A directional light by power (u0): wi against its direction, Le-like factor E, pdf = pick,
// unbounded shadow ray.
MCL_INLINE LightSample directional_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin,
                                                float u0, float u1, float u2) {
  (void)origin;
  (void)u1;
  (void)u2;
  MCL_GLOBAL const LightRecord* r =
      &ls.records[pick_light_record(ls.records, f->directionalFirst, f->directionalCount, u0)];
  return delta_light_sample(xyz(r->direction) * -1.0f, xyz(r->intensity), r->direction.w, INFINITY, 1);
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
