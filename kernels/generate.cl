// generate: reads FrameParams; writes one camera ray per wave item to rays[0 .. waveCount).
#include "shared/stages.h"

__kernel void generate(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                       __global Ray* rays) {
  uint i = get_global_id(0);
  if (i < waveCount) stage_generate(frame, waveStart, i, rays);
}
