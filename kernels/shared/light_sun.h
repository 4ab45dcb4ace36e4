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

// A sun by power (u0), a direction uniform in its cone (u1, u2): cos theta = 1 - u1 (1 - cos alpha),
// sin theta from the same product (exact for tiny disks, where 1 - cos theta rounds away).
MCL_INLINE LightSample sun_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float u0,
                                        float u1, float u2) {
  (void)origin;
  MCL_GLOBAL const LightRecord* r = &ls.records[pick_light_record(ls.records, f->sunFirst, f->sunCount, u0)];
  float3 axis = xyz(r->direction) * -1.0f;
  float h = u1 * r->cone.z;  // 1 - cos theta
  float cosT = 1.0f - h;
  float sinT = sqrt(fmax(h * (2.0f - h), 0.0f));
  float sp, cp;
  mcl_sincos_turns(u2, &sp, &cp);  // the portable sine and cosine (same bits on every device)
  float3 wi = to_world(make_float3(sinT * cp, sinT * sp, cosT), axis);
  return delta_light_sample(wi, xyz(r->intensity), r->direction.w / r->cone.y, INFINITY, 1);
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
