// generate: reads the frame's camera and the active-pixel list; writes the camera ray of each wave
// item to rays[0 .. waveCount) (pinhole, or thin lens with the aperture point from MCL_DIM_LENS).
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_generate(const generate_args* a, uint i) {
  if (i >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  uint pixel = item_pixel(f, a->active, a->waveStart, i);
  uint sample = item_sample(f, a->waveStart, i);
  float4 u = sample_uniform4(f, pixel, sample, MCL_DIM_CAMERA);
  float px = (float)(pixel % f->width) + u.x;
  float py = (float)(pixel / f->width) + u.y;
  if (f->lensRadius > 0.0f) {
    float4 l = sample_uniform4(f, pixel, sample, MCL_DIM_LENS);
    a->rays[i] = camera_ray_lens(f, px, py, l.x, l.y);
  } else {
    a->rays[i] = camera_ray(f, px, py);
  }
}
