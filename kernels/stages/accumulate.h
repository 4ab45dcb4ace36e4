// accumulate: reads each wave item's radiance and shadow slots and the active-pixel list; for the
// j-th pixel touched by the wave, adds each of its samples in the wave, in sample order, to the
// pixel's running mean (rgb, w = sample count n) and M2 (rgb: sum of squared deviations from the
// mean), by Welford's update: no cancellation when the variance is small against the mean.
// One work item per touched pixel.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_accumulate(const accumulate_args* a, uint j) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  if (j >= a->waveCount || j >= f->activeCount) return;  // j < pixels touched by the wave
  uint pixel = item_pixel(f, a->active, a->waveStart, j);
  float4 m = a->mean[pixel];
  float4 q = a->m2[pixel];
  // float4 throughout (w lanes zeroed): no float3, whose padding lane simulators flag as undefined.
  for (uint i = j; i < a->waveCount; i += f->activeCount) {
    float4 value = a->radiance[i];
    for (uint k = 0; k < f->shadowSlots; ++k) value += a->shadowContrib[i * f->shadowSlots + k];
    value.w = 0.0f;
    float n = m.w + 1.0f;
    float4 delta = value - m;
    delta.w = 0.0f;
    float4 updated = m + delta / n;
    updated.w = n;
    float4 spread = delta * (value - updated);
    spread.w = 0.0f;
    m = updated;
    q += spread;
  }
  a->mean[pixel] = m;
  a->m2[pixel] = q;
}
