// camera.h: the camera ray through a point of the image plane. Pixel (px, py) is sampled at
// (px + u, py + v), u, v in [0, 1) (box filter); row 0 is the top of the image. A pinhole, or a
// thin lens (FrameParams::lensRadius > 0): the ray starts at a point of the aperture disk
// (lens_u, lens_v in [0, 1), concentric map) and passes through the pinhole ray's point on the
// plane in focus, FrameParams::focusDistance along the view direction. A lens radius of 0 is
// exactly the pinhole (the lens numbers are not used).
#pragma once
#include "sampling.h"
#include "types.h"

MCL_INLINE Ray camera_ray(MCL_CONSTANT const FrameParams* f, float x, float y) {
  float3 d = xyz(f->camTopLeft) + xyz(f->camDx) * x + xyz(f->camDy) * y;
  Ray r;
  r.origin = with_w(xyz(f->camOrigin), 0.0f);
  r.dir = with_w(normalize(d), INFINITY);
  return r;
}

MCL_INLINE Ray camera_ray_lens(MCL_CONSTANT const FrameParams* f, float x, float y, float lens_u, float lens_v) {
  if (!(f->lensRadius > 0.0f)) return camera_ray(f, x, y);
  // d's component along the view direction is 1 (camDx, camDy are perpendicular to it), so
  // origin + d * focusDistance lies on the plane in focus.
  float3 d = xyz(f->camTopLeft) + xyz(f->camDx) * x + xyz(f->camDy) * y;
  float3 focus = xyz(f->camOrigin) + d * f->focusDistance;
  float2 disk = sample_concentric_disk(lens_u, lens_v);
  float3 right = normalize(xyz(f->camDx)), up = normalize(xyz(f->camDy)) * -1.0f;
  float3 origin = xyz(f->camOrigin) + right * (disk.x * f->lensRadius) + up * (disk.y * f->lensRadius);
  Ray r;
  r.origin = with_w(origin, 0.0f);
  r.dir = with_w(normalize(focus - origin), INFINITY);
  return r;
}
