// path_gather: after intersect_shadow, for each path shaded this bounce (the queue pathIds[0 ..
// *rayCount); identity at bounce 0), adds its shadow slots (the unblocked next-event estimates, in
// slot order) to radiance[id] and clears them, so the sum does not depend on the queue's order and
// accumulate later adds zeros.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_path_gather(const path_gather_args* a, uint k) {
  if (k >= *a->rayCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  uint id = a->pathBounce == 0 ? k : a->pathIds[k];
  float4 sum = a->radiance[id];
  for (uint s = 0; s < f->shadowSlots; ++s) {
    sum += a->shadowContrib[id * f->shadowSlots + s];
    a->shadowContrib[id * f->shadowSlots + s] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  }
  sum.w = 0.0f;
  a->radiance[id] = sum;
}
