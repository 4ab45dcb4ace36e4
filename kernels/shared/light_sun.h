// light_sun.h: the light kind "sun" (light_kinds.h): a disk infinitely far away of angular radius
// alpha, uniform radiance L = E / (pi sin^2 alpha) so that a surface facing it receives irradiance
// E (W/m^2); directions sampled uniformly in its cone (pdf 1 / solid angle). Reached by next-event
// estimation only: BSDF rays never see it (no geometry, not part of the environment), so its samples
// take no MIS weight (LightSample.delta = 1, although its pdf is per solid angle). Reads FrameParams
// and the light records (direction: the way the light travels; intensity: L; cone: x cos alpha,
// y solid angle 2 pi (1 - cos alpha), z 1 - cos alpha, from double on the host); pure; compiled by
// the kernels and the host.
#pragma once
#include "light_records.h"
#include "sampling.h"

MCL_INLINE float sun_light_probability(MCL_CONSTANT const FrameParams* f) { return f->shareSun; }

// The sample of the sun travelling along `direction` with radiance L and cone `cone`, picked with
// probability `pick`: a direction uniform in its cone (u1, u2): cos theta = 1 - u1 (1 - cos alpha),
// sin theta from the same product (exact for tiny disks, where 1 - cos theta rounds away); pdf
// pick / solid angle. Written once for floats and lanes (the parameters of
// MCL_DEFINE_DELTA_LIGHT_SAMPLE, and the portable sine and cosine's prefix S: the same bits on
// every device).
#define MCL_DEFINE_SUN_LIGHT(P, F, F3, F4, M, V, LS, S)                                                   \
  MCL_INLINE LS P##sun_light_at(F3 direction, F3 radiance, F pick, F4 cone, F u1, F u2) {                 \
    F3 axis = V##_scale(direction, -1.0f);                                                                \
    F h = u1 * cone.z; /* 1 - cos theta */                                                                \
    F cosT = 1.0f - h;                                                                                    \
    F sinT = sqrt(fmax(h * (2.0f - h), 0.0f));                                                            \
    F sp, cp;                                                                                             \
    S##sincos_turns(u2, &sp, &cp);                                                                        \
    F3 wi = P##to_world(V##_make(sinT * cp, sinT * sp, cosT), axis);                                      \
    return P##delta_light_sample(wi, radiance, pick / cone.y, (F)(INFINITY), (F)(0.0f) == (F)(0.0f));     \
  }
MCL_DEFINE_SUN_LIGHT(, float, float3, float4, int, f3, LightSample, mcl_)

// A sun by power (u0): sun_light_at the picked record, the direction from u1, u2.
MCL_INLINE LightSample sun_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float u0,
                                        float u1, float u2) {
  (void)origin;
  MCL_GLOBAL const LightRecord* r = &ls.records[pick_light_record(ls.records, f->sunFirst, f->sunCount, u0)];
  return sun_light_at(xyz(r->direction), xyz(r->intensity), r->direction.w, r->cone, u1, u2);
}

// Not reachable by BSDF rays (see above).
MCL_INLINE float sun_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return 0.0f;
}

MCL_INLINE float3 sun_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  (void)ls;
  (void)hit;
  return make_float3(0.0f, 0.0f, 0.0f);
}
