// light_records.h: what the record-based light kinds (light_point.h, light_spot.h,
// light_directional.h) share: picking one LightRecord of a kind's range by power, and the
// LightSample of a delta light. Reads the light-record table; pure; compiled by the kernels and
// the host.
#pragma once
#include "light_scene.h"

// Index of the first record in [first, first + count) whose cdf (position.w) exceeds u (binary
// search, as pick_emitter); count > 0.
MCL_INLINE uint pick_light_record(MCL_GLOBAL const LightRecord* records, uint first, uint count, float u) {
  uint lo = first, hi = first + count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (records[mid].position.w > u) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

// A delta light's sample: direction wi, the radiance-like factor le (the contribution is
// f * le * cos / pdf) and pdf the discrete probability of picking it (no solid angle: nothing
// else can produce this direction, so it takes no MIS weight). ok = 0 gives no sample.
MCL_INLINE LightSample delta_light_sample(float3 wi, float3 le, float pick, float tmax, int ok) {
  LightSample s = no_light_sample();
  s.wi = ok ? wi : s.wi;
  s.le = ok ? le : s.le;
  s.pdf = ok ? pick : 0.0f;
  s.tmax = tmax;
  s.delta = 1;
  return s;
}
