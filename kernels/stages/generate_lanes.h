// generate_lanes.h: the packet form of generate (generate.h): the camera rays of W consecutive wave
// items, one per lane, the same bits as the scalar body. Thin-lens cameras and a partial last
// packet run the scalar body per item.
#pragma once
#include "generate.h"
#include "stage_lanes.h"

MCL_INLINE void stage_generate_lanes(const generate_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  if (v_packet_partial(first, a->waveCount) || f->lensRadius > 0.0f) {
    for (uint k = 0; k < MCL_LANES && first + k < a->waveCount; ++k) stage_generate(a, first + k);
    return;
  }
  vuint pixel, sample;
  v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
  vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_CAMERA);
  vuint row, column;
  v_divmod(pixel, f->width, &row, &column);
  vfloat px = v_cvt_f_u(column) + u.x;
  vfloat py = v_cvt_f_u(row) + u.y;
  // camera_ray: d = topLeft + dx * x + dy * y, normalised.
  vfloat3 d = v3_add(v3_add(v3_splat(xyz(f->camTopLeft)), v3_scale(v3_splat(xyz(f->camDx)), px)),
                     v3_scale(v3_splat(xyz(f->camDy)), py));
  vfloat3 n = v3_normalize(d);
  MCL_GLOBAL float* r = (MCL_GLOBAL float*)(a->rays + first);
  v_store4_stride(r, 8, v_f(f->camOrigin.x), v_f(f->camOrigin.y), v_f(f->camOrigin.z), v_f(0.0f));
  v_store4_stride(r + 4, 8, n.x, n.y, n.z, v_f(INFINITY));
}
