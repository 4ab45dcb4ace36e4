// generate: reads the frame's camera and the active-pixel list; writes the camera rays of wave items
// first .. first + W - 1, one per lane (W = MCL_LANES: 1 on the host backend and GPUs), to rays[]
// below waveCount: pinhole, or thin lens with the aperture point from MCL_DIM_LENS (camera.h's
// operations per lane); the offset within the pixel drawn from the pixel filter (filter_offset). Lanes past the wave compute some item's ray and store nothing.
#pragma once
#include "stage_lanes.h"

MCL_INLINE void stage_generate(const generate_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  vuint pixel, sample;
  v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
  vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_CAMERA);
  vuint row, column;
  v_divmod(pixel, f->width, &row, &column);
  vfloat px = v_cvt_f_u(column) + v_filter_offset(f, u.x);
  vfloat py = v_cvt_f_u(row) + v_filter_offset(f, u.y);
  vfloat3 origin = v3_splat(xyz(f->camOrigin)), d = v_camera_direction(f, px, py);
  if (f->lensRadius > 0.0f) {
    vfloat4 l = v_sample_uniform4(f, pixel, sample, MCL_DIM_LENS);
    v_camera_lens(f, l.x, l.y, &origin, &d);
  }
  vfloat3 n = v3_normalize(d);
  const uint lanes = v_packet_lanes(first, a->waveCount);
  MCL_GLOBAL float* r = (MCL_GLOBAL float*)(a->rays + first);
  v_store4_stride_n(r, 8, lanes, origin.x, origin.y, origin.z, v_f(0.0f));
  v_store4_stride_n(r + 4, 8, lanes, n.x, n.y, n.z, v_f(INFINITY));
}
