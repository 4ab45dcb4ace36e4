// light_records.h: what the record-based light kinds (light_point.h, light_spot.h,
// light_directional.h) share: picking one LightRecord of a kind's range by power, and the
// LightSample of a delta light. Reads the light-record table; pure; compiled by the kernels and
// the host.
#pragma once
#include "lanes.h"  // vsel and the float3 operations under the lanes' names
#include "light_scene.h"

// Index of the first record in [first, first + count) whose cdf (position.w) exceeds u (binary
// search, as pick_emitter; count > 0), where m is set (elsewhere `first`). Written once for floats
// and lanes (P, F, U, M, ANY, G: the prefix, float, uint, int mask, any, mcl_gather_float's prefix
// here; the lanes' in stages/lane_lights.h): the same halving steps, each lane's record read
// by a gather.
#define MCL_DEFINE_PICK_LIGHT_RECORD(P, F, U, M, ANY, G)                                                       \
  MCL_INLINE U P##pick_light_record_of(MCL_GLOBAL const LightRecord* records, uint first, uint count, F u, M m) { \
    MCL_GLOBAL const float* cdf = (MCL_GLOBAL const float*)records + 3; /* position.w */                       \
    const uint stride = (uint)(sizeof(LightRecord) / sizeof(float));                                           \
    U lo = (U)(first), hi = vsel(m, (U)(first + count - 1u), (U)(first));                                     \
    for (;;) {                                                                                                 \
      M on = lo < hi;                                                                                          \
      if (!ANY(on)) break;                                                                                     \
      U mid = (lo + hi) / 2u;                                                                                  \
      M right = G##gather_float(cdf, vsel(on, mid, (U)(first)), stride) > u;                                  \
      hi = vsel(on & right, mid, hi);                                                                          \
      lo = vsel(on & (right == (M)(0)), mid + 1u, lo);                                                         \
    }                                                                                                          \
    return lo;                                                                                                 \
  }
MCL_DEFINE_PICK_LIGHT_RECORD(, float, uint, int, MCL_ANY1, mcl_)
MCL_INLINE uint pick_light_record(MCL_GLOBAL const LightRecord* records, uint first, uint count, float u) {
  return pick_light_record_of(records, first, count, u, 1);
}

// A delta light's sample: direction wi, the radiance-like factor le (the contribution is
// f * le * cos / pdf) and pdf the discrete probability of picking it (no solid angle: nothing
// else can produce this direction, so it takes no MIS weight). ok unset gives no sample (the
// fields of no_light_sample). Written once for floats and lanes (P, F, F3, M, V, LS: the prefix,
// float, float3, int mask, f3, LightSample here; v_, vfloat, vfloat3, vmask, v3, VLightSample in
// stages/lane_lights.h), as the record kinds' samples at a picked record (light_point.h,
// light_spot.h, light_directional.h, light_sun.h) are.
#define MCL_DEFINE_DELTA_LIGHT_SAMPLE(P, F, F3, M, V, LS)                                   \
  MCL_INLINE LS P##delta_light_sample(F3 wi, F3 le, F pick, F tmax, M ok) {                \
    LS s;                                                                                  \
    s.wi = V##_select(ok, wi, V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f)));                  \
    s.le = V##_select(ok, le, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                  \
    s.pdf = vsel(ok, pick, (F)(0.0f));                                                     \
    s.tmax = tmax;                                                                         \
    s.delta = ok == ok; /* every lane: a delta light */                                    \
    return s;                                                                              \
  }
MCL_DEFINE_DELTA_LIGHT_SAMPLE(, float, float3, int, f3, LightSample)
