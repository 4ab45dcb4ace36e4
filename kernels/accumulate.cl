// accumulate: reads each wave item's radiance and shadow slots; adds them per pixel, in sample
// order, to the running sum (rgb + count) and sum of squares. One work item per touched pixel.
#include "shared/stages.h"

__kernel void accumulate(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                         __global const float4* radiance, __global const float4* shadowContrib,
                         __global float4* sum, __global float4* sumSq) {
  uint j = get_global_id(0);
  uint pixels = frame->width * frame->height;
  if (j < min(waveCount, pixels))
    stage_accumulate(frame, waveStart, waveCount, j, radiance, shadowContrib, sum, sumSq);
}
