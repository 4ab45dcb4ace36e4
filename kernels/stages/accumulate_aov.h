// accumulate_aov: reads each wave item's AOVs and the active-pixel list; adds the AOVs of the j-th
// touched pixel's samples in the wave (its runs, accumulate.h), in sample order, to aovSum[2 pixel] (albedo, depth) and
// aovSum[2 pixel + 1] (normal). One work item per touched pixel.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_accumulate_aov(const accumulate_aov_args* a, uint j) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint shift = f->sampleBlockShift, ac = f->activeCount;
  if (j >= wave_touched_pixels(a->waveStart, a->waveCount, shift, ac)) return;
  uint pixel = a->active[(uint)(((a->waveStart >> shift) + j) % ac)];  // as accumulate.h
  float4 s0 = a->aovSum[2 * pixel];
  float4 s1 = a->aovSum[2 * pixel + 1];
  const ulong g0 = a->waveStart, g1 = g0 + a->waveCount;
  for (ulong q = (g0 >> shift) + j; (q << shift) < g1; q += ac) {
    uint first, end;
    wave_run_items(g0, a->waveCount, shift, q, &first, &end);
    for (uint i = first; i < end; ++i) {
      s0 += a->aov[2 * i];
      s1 += a->aov[2 * i + 1];
    }
  }
  a->aovSum[2 * pixel] = s0;
  a->aovSum[2 * pixel + 1] = s1;
}
