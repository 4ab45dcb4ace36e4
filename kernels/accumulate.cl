// accumulate: reads each wave item's radiance and shadow slots and the active-pixel list; adds
// them per pixel, in sample order, to the running mean (rgb + count) and M2 (Welford). One work
// item per touched pixel.
#include "shared/stages.h"

__kernel void accumulate(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                         __global const float4* radiance, __global const float4* shadowContrib,
                         __global float4* mean, __global float4* m2,
                         __global const uint* active) {
  uint j = get_global_id(0);
  if (j < min(waveCount, frame->activeCount))
    stage_accumulate(frame, active, waveStart, waveCount, j, radiance, shadowContrib, mean, m2);
}
