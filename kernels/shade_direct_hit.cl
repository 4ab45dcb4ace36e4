// shade_direct_hit: reads each item's BRDF ray and its closest hit; writes the emitted light it
// found (MIS-weighted) to the item's BRDF shadow slot.
#include "shared/stages_direct.h"

__kernel void shade_direct_hit(__constant FrameParams* frame, uint waveCount,
                               __global const Triangle* tris, __global const Material* materials,
                               __global const Ray* rays, __global const Hit* hits,
                               __global const Ray* bounce, __global const Hit* bounceHits,
                               __global float4* shadowContrib) {
  uint i = get_global_id(0);
  if (i < waveCount)
    stage_shade_direct_hit(frame, tris, materials, rays, hits, bounce, bounceHits, i,
                           shadowContrib);
}
