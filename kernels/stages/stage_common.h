// stage_common.h: what several stage bodies share: the pixel and sample of a wave item, the
// surface at a hit (shared/surface.h), the shadow queue.
// Pure functions of their arguments; compiled by the kernels and by the host backend.
// A wave holds `waveCount` consecutive indices g = waveStart + i of the round's items, in blocks of
// C = 2^sampleBlockShift samples per pixel: run q = g / C is pixel active[q % activeCount], and item
// g is its sample (q / activeCount) C + g % C. So C consecutive items are C samples of one pixel
// (a packet's camera rays are then coherent), every pixel gets its samples block by block, and a
// pixel's samples are accumulated in sample order whatever the wave size or C (C = 1: sample-major,
// pixel = active[g % activeCount], sample = g / activeCount). The host picks C per round so that
// it divides the round's first sample and sample count (host/render/wavefront.cpp). Without
// adaptive sampling the list holds every pixel in order.
#pragma once
#include "../shared/camera.h"
#include "../shared/lights.h"
#include "../shared/sampler.h"
#include "../shared/sampling.h"
#include "../shared/shading.h"
#include "../shared/stage_table.h"
#include "../shared/surface.h"
#include "../shared/surface_texture.h"

// The alpha test of a traversal stage (its arguments hold MCL_ALPHA_ARGS), built in `as`: &as, or
// null when no triangle is alpha-tested (FrameParams::alphaTested).
#define MCL_STAGE_ALPHA(a, as)                                                                          \
  ((as) = make_alpha_scene((a)->materials, (a)->shading,                                                \
                           make_texture_tables((a)->textures, (a)->textureLevels, (a)->texels)),        \
   (a)->frame->alphaTested ? &(as) : (const AlphaScene*)0)

// The instance of hit i of a hit buffer (its hitInstances buffer), MCL_NO_INSTANCE for a world-space
// triangle; without a two-level BVH the buffer is a 1-entry dummy and never read.
MCL_INLINE uint hit_instance(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* hitInstances, uint i) {
  return f->instanceCount > 0u ? hitInstances[i] : MCL_NO_INSTANCE;
}

// The pixel and the sample index of wave item i.
MCL_INLINE uint item_pixel(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                           ulong waveStart, uint i) {
  return active[(uint)(((waveStart + i) >> f->sampleBlockShift) % f->activeCount)];
}
MCL_INLINE uint item_sample(MCL_CONSTANT const FrameParams* f, ulong waveStart, uint i) {
  const uint c = f->sampleBlockShift;
  const ulong g = waveStart + i;
  return ((uint)((g >> c) / f->activeCount) << c) | ((uint)g & ((1u << c) - 1u));
}

// The round's block shift: the largest C = 2^shift <= lanes that divides the round's first sample
// and its sample count (lanes: the packet width W, a power of two; C = 1 on the host backend).
MCL_INLINE uint sample_block_shift(uint lanes, ulong firstSample, ulong samples) {
  uint shift = 0u;
  while ((2u << shift) <= lanes && ((firstSample | samples) & ((2ul << shift) - 1u)) == 0u) ++shift;
  return shift;
}

// The pixels a wave touches: runs q0 .. q1 of its items, so min(activeCount, q1 - q0 + 1) pixels,
// the j-th of them active[(q0 + j) % activeCount] (accumulate's work items).
MCL_INLINE uint wave_touched_pixels(ulong waveStart, uint waveCount, uint shift, uint activeCount) {
  if (waveCount == 0u) return 0u;
  ulong runs = ((waveStart + waveCount - 1u) >> shift) - (waveStart >> shift) + 1u;
  return runs < (ulong)activeCount ? (uint)runs : activeCount;
}
// Wave items [*first, *end) of run q (which may start before the wave and end after it).
MCL_INLINE void wave_run_items(ulong waveStart, uint waveCount, uint shift, ulong q, uint* first, uint* end) {
  const ulong g1 = waveStart + waveCount, rs = q << shift, re = (q + 1u) << shift;
  *first = (uint)((rs > waveStart ? rs : waveStart) - waveStart);
  *end = (uint)((re < g1 ? re : g1) - waveStart);
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
