// accumulate_aov: reads each wave item's AOVs and the active-pixel list; adds the AOVs of the j-th
// touched pixel's samples in the wave (its runs, accumulate.h), in sample order, to
// aovSum[MCL_AOV_VECTORS pixel + v] (v: (albedo, depth), (normal, 0), (emission, 0); record_aov.h).
// Touched pixels j0 .. j0 + W - 1, one per lane, walking their runs together (run_walk).
#pragma once
#include "stage_lanes.h"

MCL_INLINE void stage_accumulate_aov(const accumulate_aov_args* a, uint j0) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint limit = wave_touched_pixels(a->waveStart, a->waveCount, f->sampleBlockShift, f->activeCount);
  if (j0 >= limit) return;
  const uint lanes = v_packet_lanes(j0, limit), stride = 4u * MCL_AOV_VECTORS;
  RunWalk walk;
  vuint pixel = run_walk_begin(&walk, f, a->active, a->waveStart, a->waveCount, j0, lanes);
  MCL_GLOBAL float* sum = (MCL_GLOBAL float*)a->aovSum;
  MCL_GLOBAL const float* aov = (MCL_GLOBAL const float*)a->aov;
  vfloat sx[MCL_AOV_VECTORS], sy[MCL_AOV_VECTORS], sz[MCL_AOV_VECTORS], sw[MCL_AOV_VECTORS];
  for (uint v = 0; v < MCL_AOV_VECTORS; ++v) v_gather4(sum + 4u * v, pixel, stride, &sx[v], &sy[v], &sz[v], &sw[v]);
  for (vmask step = run_walk_step(&walk); v_any(step); step = run_walk_step(&walk)) {
    vuint at = vsel(step, walk.i, v_u(0u));  // masked lanes read item 0
    for (uint v = 0; v < MCL_AOV_VECTORS; ++v) {
      vfloat x, y, z, w;
      v_gather4(aov + 4u * v, at, stride, &x, &y, &z, &w);
      sx[v] = vsel(step, sx[v] + x, sx[v]);
      sy[v] = vsel(step, sy[v] + y, sy[v]);
      sz[v] = vsel(step, sz[v] + z, sz[v]);
      sw[v] = vsel(step, sw[v] + w, sw[v]);
    }
    walk.i = walk.i + v_mask01(step);
  }
  for (uint v = 0; v < MCL_AOV_VECTORS; ++v) v_scatter4_n(sum + 4u * v, pixel, stride, lanes, sx[v], sy[v], sz[v], sw[v]);
}
