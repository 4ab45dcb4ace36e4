// camera.h: the camera ray through a point of the image plane, and the pixel filter's warp of a
// sample's offset within its pixel (filter_offset); row 0 is the top of the image. A pinhole, or a
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
// filter_offset: a uniform u in [0, 1) warped to an offset from the pixel's left (top) edge, drawn
// from the pixel filter (FrameParams::filterKind, filterRadius; x and y each their own u): the
// filter is importance sampled, so every sample keeps weight 1 and the film stays a plain mean.
// Box: (0.5 - r) + 2 r u, which for the default r = 0.5 is exactly u (the image before filters).
// Triangle: the tent's inverse CDF, 0.5 + r (sqrt(2u) - 1) below u = 1/2, mirrored above.
// Table: the bin k whose CDF range holds u (a scan of every bin with selects, the same steps in
// every lane), then linearly within it: piecewise-constant density.
#define MCL_DEFINE_CAMERA(P, F, F3, V)                                                                   \
  MCL_INLINE F P##filter_offset(MCL_CONSTANT const FrameParams* f, F u) {                               \
    const float r = f->filterRadius;                                                                    \
    if (f->filterKind == MCL_FILTER_TRIANGLE) {                                                         \
      F t = vsel(u < 0.5f, sqrt(2.0f * u) - 1.0f, 1.0f - sqrt(2.0f - 2.0f * u));                        \
      return 0.5f + t * r;                                                                              \
    }                                                                                                   \
    if (f->filterKind == MCL_FILTER_TABLE) {                                                            \
      F lo = (F)(0.0f), hi = (F)(f->filterCdf[0]), k = (F)(0.0f);                                       \
      for (int i = 0; i < MCL_FILTER_BINS - 1; ++i) {                                                   \
        const float c = f->filterCdf[i];                                                                \
        lo = vsel(u >= c, (F)(c), lo);                                                                  \
        hi = vsel(u >= c, (F)(f->filterCdf[i + 1]), hi);                                                \
        k = vsel(u >= c, (F)((float)(i + 1)), k);                                                       \
      }                                                                                                 \
      F t = vsel(hi > lo, (u - lo) / (hi - lo), (F)(0.5f));                                             \
      return 0.5f + ((k + fmin(t, (F)(1.0f))) * (2.0f * r / (float)MCL_FILTER_BINS) - r);              \
    }                                                                                                   \
    return (0.5f - r) + u * (2.0f * r);                                                                 \
  }                                                                                                     \
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
