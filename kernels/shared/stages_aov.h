// stages_aov.h: the first-hit AOVs denoisers take as inputs, per wave item and per pixel: albedo
// (Kd), the geometric normal facing the camera, and depth (distance along the camera ray). Zero
// where the camera ray hits nothing. Shared by the kernels and the host backend.
#pragma once
#include "lights.h"
#include "stages.h"

// record_aov: writes aov[2i] = (albedo, depth) and aov[2i + 1] = (normal, 0) for item i.
MCL_INLINE void stage_record_aov(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const Material* materials,
                                 MCL_GLOBAL const Ray* rays, MCL_GLOBAL const Hit* hits, uint i,
                                 MCL_GLOBAL float4* aov) {
  Hit h = hits[i];
  if (h.tri == MCL_NO_HIT) {
    aov[2 * i] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    aov[2 * i + 1] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    return;
  }
  MCL_GLOBAL const Triangle* tri = &tris[h.tri];
  aov[2 * i] = with_w(xyz(materials[triangle_material(tri)].albedo), h.t);
  aov[2 * i + 1] = with_w(facing_normal(tri, xyz(rays[i].dir)), 0.0f);
}

// accumulate_aov: adds the AOVs of the j-th touched pixel's samples in the wave, in sample order,
// to aovSum[2 pixel] (albedo, depth) and aovSum[2 pixel + 1] (normal).
MCL_INLINE void stage_accumulate_aov(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                                     ulong waveStart, uint waveCount, uint j,
                                     MCL_GLOBAL const float4* aov, MCL_GLOBAL float4* aovSum) {
  uint pixel = item_pixel(f, active, waveStart, j);
  float4 a = aovSum[2 * pixel];
  float4 b = aovSum[2 * pixel + 1];
  for (uint i = j; i < waveCount; i += f->activeCount) {
    a += aov[2 * i];
    b += aov[2 * i + 1];
  }
  aovSum[2 * pixel] = a;
  aovSum[2 * pixel + 1] = b;
}
