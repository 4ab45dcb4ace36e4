// shade_direct: reads camera rays, hits, materials and the emitter table; writes radiance (Le seen
// directly, or background), pushes light-sample occlusion queries onto the shadow queue and
// writes one BRDF-sampled ray per item to bounce (inactive: tmax < 0).
#include "shared/stages_direct.h"

__kernel void shade_direct(__constant FrameParams* frame, ulong waveStart, uint waveCount,
                           __global const Triangle* tris, __global const Material* materials,
                           __global const Emitter* emitters, __global const Ray* rays,
                           __global const Hit* hits, __global float4* radiance,
                           __global float4* shadowContrib, __global ShadowWork* queue,
                           __global volatile uint* queueCount, __global Ray* bounce,
                           __global const uint* active) {
  uint i = get_global_id(0);
  if (i < waveCount)
    stage_shade_direct(frame, active, waveStart, tris, materials, emitters, rays, hits, i, radiance,
                       shadowContrib, queue, queueCount, bounce);
}
