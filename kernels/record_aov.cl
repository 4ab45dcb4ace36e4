// record_aov: reads camera rays, their hits, triangles and materials; writes each item's
// first-hit albedo, depth and facing normal to aov (two float4 per item).
#include "shared/stages_aov.h"

__kernel void record_aov(__global const Triangle* tris, __global const Material* materials,
                         __global const Ray* rays, __global const Hit* hits, uint waveCount,
                         __global float4* aov) {
  uint i = get_global_id(0);
  if (i < waveCount) stage_record_aov(tris, materials, rays, hits, i, aov);
}
