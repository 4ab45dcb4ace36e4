// generate: reads FrameParams and the active-pixel list; writes one camera ray per wave item to
// rays[0 .. waveCount).
#include "shared/stages.h"

__kernel void generate(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                       __global Ray* rays, __global const uint* active) {
  uint i = get_global_id(0);
  if (i < waveCount) stage_generate(frame, active, waveStart, i, rays);
}
