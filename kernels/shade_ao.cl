// shade_ao: reads camera rays and their hits; writes radiance (background or 0), clears shadow
// slots, and pushes one AO occlusion query per hit onto the shadow queue (atomic counter).
#include "shared/stages.h"

__kernel void shade_ao(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                       __global const Triangle* tris, __global const Ray* rays,
                       __global const Hit* hits, __global float4* radiance,
                       __global float4* shadowContrib, __global ShadowWork* queue,
                       __global volatile uint* queueCount, __global const uint* active) {
  uint i = get_global_id(0);
  if (i < waveCount)
    stage_shade_ao(frame, active, waveStart, tris, rays, hits, i, radiance, shadowContrib, queue,
                   queueCount);
}
