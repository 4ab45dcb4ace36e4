// light_point.h: the light kind "point" (light_kinds.h): an isotropic point of intensity I (W/sr)
// from the light-record table; a delta light: reached only by next-event estimation, never by a
// BSDF ray. Reads FrameParams and the light records; pure; compiled by the kernels and the host.
#pragma once
#include "light_records.h"

MCL_INLINE float point_light_probability(MCL_CONSTANT const FrameParams* f) { return f->sharePoint; }

// The sample of the point light at `position` of intensity I picked with probability `pick`, from
// origin: the direction toward it, Le-like factor I / r^2, pdf = pick. Written once for floats and
// lanes (the parameters of MCL_DEFINE_DELTA_LIGHT_SAMPLE).
#define MCL_DEFINE_POINT_LIGHT(P, F, F3, M, V, LS)                                                        \
  MCL_INLINE LS P##point_light_at(F3 position, F3 intensity, F pick, F3 origin) {                         \
    F3 toLight = V##_sub(position, origin);                                                               \
    F dist2 = V##_dot(toLight, toLight);                                                                  \
    F dist = sqrt(dist2);                                                                                 \
    return P##delta_light_sample(V##_make(toLight.x / dist, toLight.y / dist, toLight.z / dist),          \
                                 V##_make(intensity.x / dist2, intensity.y / dist2, intensity.z / dist2), \
                                 pick, dist * (1.0f - 1e-4f), dist > 0.0f);                               \
  }
MCL_DEFINE_POINT_LIGHT(, float, float3, int, f3, LightSample)

// A point light by power (u0): point_light_at the picked record.
MCL_INLINE LightSample point_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin,
                                          float u0, float u1, float u2) {
  (void)u1;
  (void)u2;
  MCL_GLOBAL const LightRecord* r = &ls.records[pick_light_record(ls.records, f->pointFirst, f->pointCount, u0)];
  return point_light_at(xyz(r->position), xyz(r->intensity), r->direction.w, origin);
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
