// accumulate_aov: reads each wave item's AOVs and the active-pixel list; adds the AOVs of the j-th
// touched pixel's samples in the wave, in sample order, to aovSum[2 pixel] (albedo, depth) and
// aovSum[2 pixel + 1] (normal). One work item per touched pixel.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_accumulate_aov(const accumulate_aov_args* a, uint j) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  if (j >= a->waveCount || j >= f->activeCount) return;  // j < pixels touched by the wave
  uint pixel = item_pixel(f, a->active, a->waveStart, j);
  float4 s0 = a->aovSum[2 * pixel];
  float4 s1 = a->aovSum[2 * pixel + 1];
  for (uint i = j; i < a->waveCount; i += f->activeCount) {
    s0 += a->aov[2 * i];
    s1 += a->aov[2 * i + 1];
  }
  a->aovSum[2 * pixel] = s0;
  a->aovSum[2 * pixel + 1] = s1;
}
