// camera.h: the pinhole camera ray through a point of the image plane. Pixel (px, py) is sampled
// at (px + u, py + v), u, v in [0, 1) (box filter); row 0 is the top of the image.
#pragma once
#include "types.h"

MCL_INLINE Ray camera_ray(MCL_CONSTANT const FrameParams* f, float x, float y) {
  float3 d = xyz(f->camTopLeft) + xyz(f->camDx) * x + xyz(f->camDy) * y;
  Ray r;
  r.origin = with_w(xyz(f->camOrigin), 0.0f);
  r.dir = with_w(normalize(d), INFINITY);
  return r;
}
