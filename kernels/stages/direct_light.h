// direct_light.h: the light interface of the shade stages, dispatched on the light kind in one
// place (shared/light_kinds.h; each kind's functions in shared/light_<kind>.h): one light sample
// for next-event estimation (the kind picked by its share of samples, in table order), and the
// pdf with which light sampling would have produced a direction that BSDF sampling found (for
// MIS) and the radiance found there. Reads the emitter table, triangles, their precomputed normals
// and areas, materials and the environment's tables (LightScene); writes nothing.
#pragma once
#include "../shared/light_area.h"
#include "../shared/light_directional.h"
#include "../shared/light_environment.h"
#include "../shared/light_kinds.h"
#include "../shared/light_point.h"
#include "../shared/light_spot.h"
#include "../shared/light_sun.h"
#include "stage_common.h"

// The shadow ray of a light sample drawn from `origin` (direction wi, length tmax) that leaves
// from `from` instead (the far side of the surface, for a light seen through a transmitting lobe):
// aimed at the same light point, origin + wi * tmax / (1 - 1e-4) (the samplers' margin), and
// stopping short of it by the same margin; *tmaxFrom receives its length. Keeping wi and tmax
// would overshoot a nearby light by the offset, and the light's own triangle would block it. A
// light at infinity (tmax INFINITY) keeps wi. Written once for floats and lanes (lane_bsdf.h).
#define MCL_DEFINE_SHADOW_DIR_FROM(P, F, F3, M, V)                                                  \
  MCL_INLINE F3 P##shadow_dir_from(F3 origin, F3 from, F3 wi, F tmax, F* tmaxFrom) {               \
    M finite = tmax < INFINITY;                                                                    \
    F3 d = V##_sub(V##_add(origin, V##_scale(wi, vsel(finite, tmax * (1.0f / (1.0f - 1e-4f)), (F)(0.0f)))), from); \
    F len = sqrt(V##_dot(d, d));                                                                   \
    M ok = finite & (len > 0.0f);                                                                  \
    *tmaxFrom = vsel(ok, len * (1.0f - 1e-4f), tmax);                                              \
    return V##_select(ok, V##_scale(d, 1.0f / len), wi);                                           \
  }
MCL_DEFINE_SHADOW_DIR_FROM(, float, float3, int, f3)

// The light of a ray along wi that got hit h: the triangle hit (an area light, emitting or not),
// or the environment on a miss.
MCL_INLINE LightHit light_hit(Hit h, float3 wi) {
  LightHit l;
  l.kind = h.tri == MCL_NO_HIT ? MCL_LIGHT_environment : MCL_LIGHT_area;
  l.tri = h.tri;
  l.t = h.t;
  l.u = h.u;
  l.v = h.v;
  l.wi = wi;
  return l;
}

// u.x picks the kind: the last kind (table order) with a positive share whose share starts at or
// below u.x; u.x rescaled within that share, u.y and u.z go to the kind's sampler. The pdf is the
// kind's times its share.
MCL_INLINE LightSample sample_direct_light(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float4 u) {
  uint kind = MCL_LIGHT_KIND_COUNT;
  float before = 0.0f, start = 0.0f, share = 0.0f;
#define MCL_LIGHT_PICK(k)                                \
  {                                                      \
    float p = k##_light_probability(f);                  \
    if (p > 0.0f && u.x >= before) {                     \
      kind = MCL_LIGHT_##k;                              \
      start = before;                                    \
      share = p;                                         \
    }                                                    \
    before += p;                                         \
  }
  MCL_LIGHT_KINDS(MCL_LIGHT_PICK)
#undef MCL_LIGHT_PICK
  float u0 = (u.x - start) / share;
  LightSample s = no_light_sample();
  switch (kind) {
#define MCL_LIGHT_CASE(k) \
  case MCL_LIGHT_##k: s = k##_light_sample(f, ls, origin, u0, u.y, u.z); break;
    MCL_LIGHT_KINDS(MCL_LIGHT_CASE)
#undef MCL_LIGHT_CASE
  }
  s.pdf = share * s.pdf;
  return s;
}

// Light-sampling pdf (selection included) of reaching hit.
MCL_INLINE float light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  switch (hit.kind) {
#define MCL_LIGHT_CASE(k) \
  case MCL_LIGHT_##k: return k##_light_probability(f) * k##_light_pdf(f, ls, hit);
    MCL_LIGHT_KINDS(MCL_LIGHT_CASE)
#undef MCL_LIGHT_CASE
  }
  return 0.0f;
}

// Radiance arriving from hit along -hit.wi.
MCL_INLINE float3 light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  switch (hit.kind) {
#define MCL_LIGHT_CASE(k) \
  case MCL_LIGHT_##k: return k##_light_eval(f, ls, hit);
    MCL_LIGHT_KINDS(MCL_LIGHT_CASE)
#undef MCL_LIGHT_CASE
  }
  return make_float3(0.0f, 0.0f, 0.0f);
}
