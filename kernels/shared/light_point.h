// light_point.h: the light kind "point" (light_kinds.h): an isotropic point of intensity I (W/sr)
// from the light-record table; a delta light: reached only by next-event estimation, never by a
// BSDF ray. Reads FrameParams and the light records; pure; compiled by the kernels and the host.
#pragma once
#include "light_records.h"

MCL_INLINE float point_light_probability(MCL_CONSTANT const FrameParams* f) { return f->sharePoint; }

// A point light by power (u0); the direction toward it, Le-like factor I / r^2, pdf = pick.
MCL_INLINE LightSample point_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin,
                                          float u0, float u1, float u2) {
  (void)u1;
  (void)u2;
  MCL_GLOBAL const LightRecord* r = &ls.records[pick_light_record(ls.records, f->pointFirst, f->pointCount, u0)];
  float3 toLight = xyz(r->position) - origin;
  float dist2 = dot(toLight, toLight);
  float dist = sqrt(dist2);
  return delta_light_sample(toLight / dist, xyz(r->intensity) / dist2, r->direction.w, dist * (1.0f - 1e-4f),
                            dist > 0.0f);
}

// Delta: a BSDF ray never reaches it.
MCL_INLINE float point_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return 0.0f;
}

MCL_INLINE float3 point_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return make_float3(0.0f, 0.0f, 0.0f);
}
