// accumulate_aov: reads each wave item's AOVs and the active-pixel list; adds the AOVs of the j-th
// touched pixel's samples in the wave (its runs, accumulate.h), in sample order, to
// aovSum[MCL_AOV_VECTORS pixel + v] (v: (albedo, depth), (normal, 0), (emission, 0); record_aov.h).
// One work item per touched pixel.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_accumulate_aov(const accumulate_aov_args* a, uint j) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint shift = f->sampleBlockShift, ac = f->activeCount;
  if (j >= wave_touched_pixels(a->waveStart, a->waveCount, shift, ac)) return;
  uint pixel = a->active[(uint)(((a->waveStart >> shift) + j) % ac)];  // as accumulate.h
  float4 s[MCL_AOV_VECTORS];
  for (uint v = 0; v < MCL_AOV_VECTORS; ++v) s[v] = a->aovSum[MCL_AOV_VECTORS * pixel + v];
  const ulong g0 = a->waveStart, g1 = g0 + a->waveCount;
  for (ulong q = (g0 >> shift) + j; (q << shift) < g1; q += ac) {
    uint first, end;
    wave_run_items(g0, a->waveCount, shift, q, &first, &end);
    for (uint i = first; i < end; ++i)
      for (uint v = 0; v < MCL_AOV_VECTORS; ++v) s[v] += a->aov[MCL_AOV_VECTORS * i + v];
  }
  for (uint v = 0; v < MCL_AOV_VECTORS; ++v) a->aovSum[MCL_AOV_VECTORS * pixel + v] = s[v];
}
