// light_spot.h: the light kind "spot" (light_kinds.h): a point of intensity I (W/sr) along its
// axis with Mitsuba 3's spot falloff: 1 within the beam width of the axis, falling linearly in
// angle to 0 at the cutoff angle, 0 beyond; a delta light (next-event estimation only). Reads
// FrameParams and the light records; pure; compiled by the kernels and the host.
#pragma once
#include "light_records.h"
#include "trig.h"

// Falloff at cosTheta = cos(angle from the axis); cone: cos(cutoff), cos(beam), cutoff, 1 / (cutoff - beam).
MCL_INLINE float spot_falloff(float4 cone, float cosTheta) {
  float ramp = (cone.z - mcl_acos(fmin(fmax(cosTheta, -1.0f), 1.0f))) * cone.w;  // portable acos
  float inBeam = cosTheta >= cone.y ? 1.0f : ramp;
  return cosTheta > cone.x ? inBeam : 0.0f;
}

MCL_INLINE float spot_light_probability(MCL_CONSTANT const FrameParams* f) { return f->shareSpot; }

// A spot light by power (u0); Le-like factor I * falloff / r^2, pdf = pick.
MCL_INLINE LightSample spot_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float u0,
                                         float u1, float u2) {
  (void)u1;
  (void)u2;
  MCL_GLOBAL const LightRecord* r = &ls.records[pick_light_record(ls.records, f->spotFirst, f->spotCount, u0)];
  float3 toLight = xyz(r->position) - origin;
  float dist2 = dot(toLight, toLight);
  float dist = sqrt(dist2);
  float3 wi = toLight / dist;
  float fall = spot_falloff(r->cone, -dot(wi, xyz(r->direction)));
  return delta_light_sample(wi, xyz(r->intensity) * (fall / dist2), r->direction.w, dist * (1.0f - 1e-4f),
                            dist > 0.0f && fall > 0.0f);
}

// Delta: a BSDF ray never reaches it.
MCL_INLINE float spot_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return 0.0f;
}

MCL_INLINE float3 spot_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return make_float3(0.0f, 0.0f, 0.0f);
}
