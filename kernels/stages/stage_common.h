// stage_common.h: what several stage bodies share: the pixel and sample of a wave item, the
// surface at a hit (shared/surface.h), the shadow queue.
// Pure functions of their arguments; compiled by the kernels and by the host backend.
// A wave holds `waveCount` consecutive indices g = waveStart + i into the active-pixel list,
// sample-major: pixel = active[g % activeCount], sample = g / activeCount, so a pixel's samples
// are always accumulated in sample order whatever the wave size. Without adaptive sampling the list
// holds every pixel in order.
#pragma once
#include "../shared/camera.h"
#include "../shared/lights.h"
#include "../shared/sampler.h"
#include "../shared/sampling.h"
#include "../shared/shading.h"
#include "../shared/stage_table.h"
#include "../shared/surface.h"
#include "../shared/surface_texture.h"

// The pixel and the sample index of wave item i.
MCL_INLINE uint item_pixel(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                           ulong waveStart, uint i) {
  return active[(uint)((waveStart + i) % f->activeCount)];
}
MCL_INLINE uint item_sample(MCL_CONSTANT const FrameParams* f, ulong waveStart, uint i) {
  return (uint)((waveStart + i) / f->activeCount);
}

// Pushes an occlusion query onto the shadow queue: if nothing blocks the ray from origin along unit
// dir before tmax, contribution c goes to shadowContrib[slot] (intersect_shadow). Every shade stage
// queries visibility through this one function.
MCL_INLINE void push_shadow_query(MCL_GLOBAL ShadowWork* queue, MCL_GLOBAL volatile uint* queueCount, float3 origin,
                                  float3 dir, float tmax, float3 c, uint slot) {
  ShadowWork w;
  w.ray.origin = with_w(origin, 0.0f);
  w.ray.dir = with_w(dir, tmax);
  w.r = c.x;
  w.g = c.y;
  w.b = c.z;
  w.slot = slot;
  queue[MCL_ATOMIC_INC(queueCount)] = w;
}

// The start of every shade stage: clears item i's shadow slots (a strategy leaves the slots it does
// not use at 0) and, when the camera ray missed, writes the background to radiance[i] and returns
// 0; otherwise returns 1 and leaves radiance[i] to the caller.
MCL_INLINE int shade_begin(MCL_CONSTANT const FrameParams* f, Hit h, uint i, MCL_GLOBAL float4* radiance,
                           MCL_GLOBAL float4* shadowContrib) {
  for (uint k = 0; k < f->shadowSlots; ++k)
    shadowContrib[i * f->shadowSlots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  if (h.tri != MCL_NO_HIT) return 1;
  radiance[i] = f->background;
  return 0;
}
