// light_spot.h: the light kind "spot" (light_kinds.h): a point of intensity I (W/sr) along its
// axis with Mitsuba 3's spot falloff: 1 within the beam width of the axis, falling linearly in
// angle to 0 at the cutoff angle, 0 beyond; a delta light (next-event estimation only). Reads
// FrameParams and the light records; pure; compiled by the kernels and the host.
#pragma once
#include "light_records.h"
#include "trig.h"

// Written once for floats and lanes (the parameters of MCL_DEFINE_DELTA_LIGHT_SAMPLE, and the
// portable acos's prefix A):
// - spot_falloff: the falloff at cosTheta = cos(angle from the axis); cone: cos(cutoff),
//   cos(beam), cutoff, 1 / (cutoff - beam).
// - spot_light_at: the sample of the spot at `position` with axis `axis` (the direction it
//   shines), intensity I, picked with probability `pick`, from origin: Le-like factor
//   I * falloff / r^2, pdf = pick.
#define MCL_DEFINE_SPOT_LIGHT(P, F, F3, F4, M, V, LS, A)                                                   \
  MCL_INLINE F P##spot_falloff(F4 cone, F cosTheta) {                                                      \
    F ramp = (cone.z - A##acos(fmin(fmax(cosTheta, -1.0f), 1.0f))) * cone.w; /* portable acos */           \
    F inBeam = vsel(cosTheta >= cone.y, (F)(1.0f), ramp);                                                   \
    return vsel(cosTheta > cone.x, inBeam, (F)(0.0f));                                                      \
  }                                                                                                        \
  MCL_INLINE LS P##spot_light_at(F3 position, F3 axis, F3 intensity, F pick, F4 cone, F3 origin) {         \
    F3 toLight = V##_sub(position, origin);                                                                \
    F dist2 = V##_dot(toLight, toLight);                                                                   \
    F dist = sqrt(dist2);                                                                                  \
    F3 wi = V##_make(toLight.x / dist, toLight.y / dist, toLight.z / dist);                                \
    F fall = P##spot_falloff(cone, -V##_dot(wi, axis));                                                    \
    return P##delta_light_sample(wi, V##_scale(intensity, fall / dist2), pick, dist * (1.0f - 1e-4f),      \
                                 (dist > 0.0f) & (fall > 0.0f));                                           \
  }
MCL_DEFINE_SPOT_LIGHT(, float, float3, float4, int, f3, LightSample, mcl_)

MCL_INLINE float spot_light_probability(MCL_CONSTANT const FrameParams* f) { return f->shareSpot; }

// A spot light by power (u0); Le-like factor I * falloff / r^2, pdf = pick.
MCL_INLINE LightSample spot_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float u0,
                                         float u1, float u2) {
  (void)u1;
  (void)u2;
  MCL_GLOBAL const LightRecord* r = &ls.records[pick_light_record(ls.records, f->spotFirst, f->spotCount, u0)];
  return spot_light_at(xyz(r->position), xyz(r->direction), xyz(r->intensity), r->direction.w, r->cone, origin);
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
