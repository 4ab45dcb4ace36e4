// camera.h: the camera ray through a point of the image plane. Pixel (px, py) is sampled at
// (px + u, py + v), u, v in [0, 1) (box filter); row 0 is the top of the image. A pinhole, or a
// thin lens (FrameParams::lensRadius > 0): the ray starts at a point of the aperture disk
// (lens_u, lens_v in [0, 1), concentric map) and passes through the pinhole ray's point on the
// plane in focus, FrameParams::focusDistance along the view direction. A lens radius of 0 is
// exactly the pinhole (the lens numbers are not used).
#pragma once
#include "sampling.h"
#include "types.h"

// Written once for a float type F, its 3-vector F3 and that vector's operations V (float, float3,
// f3 here; the generate stage's lanes, stage_lanes.h), with the concentric disk of prefix P.
// camera_direction: the pinhole ray's direction through image point (x, y), not normalised.
// camera_lens: moves *origin (the pinhole) to the aperture point of lens sample (lu, lv) and turns
// *d (camera_direction's) to pass through d's point on the plane in focus: d's component along the
// view direction is 1 (camDx, camDy are perpendicular to it), so origin + d * focusDistance lies
// on that plane.
#define MCL_DEFINE_CAMERA(P, F, F3, V)                                                                   \
  MCL_INLINE F3 P##camera_direction(MCL_CONSTANT const FrameParams* f, F x, F y) {                      \
    return V##_add(V##_add(V##_splat(xyz(f->camTopLeft)), V##_scale(V##_splat(xyz(f->camDx)), x)),      \
                   V##_scale(V##_splat(xyz(f->camDy)), y));                                             \
  }                                                                                                     \
  MCL_INLINE void P##camera_lens(MCL_CONSTANT const FrameParams* f, F lu, F lv, F3* origin, F3* d) {    \
    F3 focus = V##_add(*origin, V##_scale(*d, (F)(f->focusDistance)));                                  \
    F diskX, diskY;                                                                                     \
    P##concentric_disk(lu, lv, &diskX, &diskY);                                                         \
    float3 right = normalize(xyz(f->camDx)), up = normalize(xyz(f->camDy)) * -1.0f;                     \
    *origin = V##_add(V##_add(*origin, V##_scale(V##_splat(right), diskX * f->lensRadius)),             \
                      V##_scale(V##_splat(up), diskY * f->lensRadius));                                 \
    *d = V##_sub(focus, *origin);                                                                       \
  }
MCL_DEFINE_CAMERA(, float, float3, f3)

MCL_INLINE Ray camera_ray(MCL_CONSTANT const FrameParams* f, float x, float y) {
  Ray r;
  r.origin = with_w(xyz(f->camOrigin), 0.0f);
  r.dir = with_w(normalize(camera_direction(f, x, y)), INFINITY);
  return r;
}

MCL_INLINE Ray camera_ray_lens(MCL_CONSTANT const FrameParams* f, float x, float y, float lens_u, float lens_v) {
  if (!(f->lensRadius > 0.0f)) return camera_ray(f, x, y);
  float3 origin = xyz(f->camOrigin), d = camera_direction(f, x, y);
  camera_lens(f, lens_u, lens_v, &origin, &d);
  Ray r;
  r.origin = with_w(origin, 0.0f);
  r.dir = with_w(normalize(d), INFINITY);
  return r;
}
