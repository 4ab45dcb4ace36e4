// accumulate_aov: reads each wave item's AOVs and the active-pixel list; adds them per pixel, in
// sample order, to aovSum (two float4 per pixel). One work item per touched pixel.
#include "shared/stages_aov.h"

__kernel void accumulate_aov(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                             __global const float4* aov, __global float4* aovSum,
                             __global const uint* active) {
  uint j = get_global_id(0);
  if (j < min(waveCount, frame->activeCount))
    stage_accumulate_aov(frame, active, waveStart, waveCount, j, aov, aovSum);
}
