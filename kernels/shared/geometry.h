// geometry.h: pure ray-box and ray-triangle tests and the self-intersection offset, shared by the
// kernels and the host (compiled as C++ by the tests and the reference traversal).
#pragma once
#include "lanes.h"  // vsel and the float3 operations under the lanes' names
#include "types.h"

// Min and max that ignore a NaN in their FIRST operand (the second is never NaN where they are
// used): `a < b ? a : b` is one minss/maxss on x86 and the same expression on host and device,
// where fmin/fmax's symmetric NaN handling costs a compare and a blend (or a libm call on g++).
MCL_INLINE float mcl_min_nan1(float a, float b) { return a < b ? a : b; }
MCL_INLINE float mcl_max_nan1(float a, float b) { return a > b ? a : b; }

// Slab test against the closed box [bmin, bmax]; returns the entry distance (>= 0), or INFINITY
// when the ray misses or the box lies beyond tmax. invDir may hold infinities (axis-parallel rays).
// The near and far planes of each axis are picked by the sign of invDir (-0 directions give -inf).
// A ray parallel to an axis and lying exactly in one of that axis's face planes gives 0 * inf =
// NaN there; every per-axis distance enters mcl_min_nan1/mcl_max_nan1 as the first operand against
// a non-NaN accumulator (0 or tmax first), so a NaN slab constrains nothing and the ray enters the
// box, as it must: ray_triangle counts hits on edges, which can lie in that face.
MCL_INLINE float slab_entry(float nx, float ny, float nz, float fx, float fy, float fz,
                            float tmax) {
  float tmin = mcl_max_nan1(nx, mcl_max_nan1(ny, mcl_max_nan1(nz, 0.0f)));
  float tmx = mcl_min_nan1(fx, mcl_min_nan1(fy, mcl_min_nan1(fz, tmax)));
  return tmin <= tmx ? tmin : INFINITY;
}
MCL_INLINE float ray_box(float3 org, float3 invDir, float3 bmin, float3 bmax, float tmax) {
  float nx = ((invDir.x < 0.0f ? bmax.x : bmin.x) - org.x) * invDir.x;
  float fx = ((invDir.x < 0.0f ? bmin.x : bmax.x) - org.x) * invDir.x;
  float ny = ((invDir.y < 0.0f ? bmax.y : bmin.y) - org.y) * invDir.y;
  float fy = ((invDir.y < 0.0f ? bmin.y : bmax.y) - org.y) * invDir.y;
  float nz = ((invDir.z < 0.0f ? bmax.z : bmin.z) - org.z) * invDir.z;
  float fz = ((invDir.z < 0.0f ? bmin.z : bmax.z) - org.z) * invDir.z;
  return slab_entry(nx, ny, nz, fx, fy, fz, tmax);
}

// Moller-Trumbore. Returns t in (0, tmax) and barycentrics through u, v; INFINITY on a miss.
MCL_INLINE float ray_triangle(float3 org, float3 dir, float3 v0, float3 e1, float3 e2, float tmax,
                              float* uOut, float* vOut) {
  float3 p = cross(dir, e2);
  float det = dot(e1, p);
  if (fabs(det) < 1e-30f) return INFINITY;
  float inv = 1.0f / det;
  float3 s = org - v0;
  float u = dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return INFINITY;
  float3 q = cross(s, e1);
  float v = dot(dir, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return INFINITY;
  float t = dot(e2, q) * inv;
  if (!(t > 0.0f && t < tmax)) return INFINITY;
  *uOut = u;
  *vOut = v;
  return t;
}

// Reciprocal of a direction with signed infinities for zero components (no division by zero).
// 1 when every coordinate of the ray's origin and direction is finite. A NaN or infinite ray
// defeats the slab test (its NaN distances are dropped by mcl_min_nan1/mcl_max_nan1, so it
// "enters" every box): the traversals treat it as a miss and the intersect stages count it.
// x - x is 0 for a finite x and NaN for inf or NaN (no fast-math anywhere, in either language).
MCL_INLINE int ray_is_finite(float3 org, float3 dir) {
  float z = (org.x - org.x) + (org.y - org.y) + (org.z - org.z) + (dir.x - dir.x) +
            (dir.y - dir.y) + (dir.z - dir.z);
  return z == 0.0f;
}

MCL_INLINE float3 safe_inverse(float3 d) {
  return make_float3(d.x != 0.0f ? 1.0f / d.x : copysign(INFINITY, d.x),
                     d.y != 0.0f ? 1.0f / d.y : copysign(INFINITY, d.y),
                     d.z != 0.0f ? 1.0f / d.z : copysign(INFINITY, d.z));
}

// Moves p off its surface along the normal n so that a ray leaving it does not hit the same
// triangle again: integer ULP offsets far from the origin, a small absolute one near it
// (Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", 2019). "Near"
// and "small" are relative to `scale` (FrameParams::offsetScale: 1 for scenes of unit size or
// larger, the power of two above the scene's largest coordinate for smaller ones), so a scene
// scaled by a power of two gets offsets scaled by exactly that power: tiny scenes are valid scenes.
// Written once for a float type F, its int type I, 3-vector F3 and that vector's operations V
// (float, int, float3, f3; the packet stages' lanes, stage_lanes.h), with C's float -> int
// conversion CVT_I and the bit casts AS_F (uint -> F), AS_U (F -> uint), I_AS_U (I -> uint).
#define MCL_DEFINE_OFFSET_RAY_ORIGIN(P, F, I, F3, V, CVT_I, AS_F, AS_U, I_AS_U)                 \
  MCL_INLINE F P##offset_coord(F p, F n, float scale) {                                       \
    const float origin = 1.0f / 32.0f, floatScale = 1.0f / 65536.0f, intScale = 256.0f;        \
    I of = CVT_I(intScale * n);                                                                \
    I step = vsel(p < 0.0f, -of, of);                                                          \
    F pi = AS_F(AS_U(p) + I_AS_U(step));                                                       \
    return vsel(fabs(p) < origin * scale, p + floatScale * scale * n, pi);                     \
  }                                                                                            \
  MCL_INLINE F3 P##offset_ray_origin(F3 p, F3 n, float scale) {                                \
    return V##_make(P##offset_coord(p.x, n.x, scale), P##offset_coord(p.y, n.y, scale),        \
                    P##offset_coord(p.z, n.z, scale));                                         \
  }
MCL_DEFINE_OFFSET_RAY_ORIGIN(, float, int, float3, f3, (int), as_float, as_uint, (uint))

// cross(a, b) of a and b each divided by its largest absolute component: of order 1 for any
// non-degenerate triangle's edges, however small (cross(e1, e2) of edges ~1e-15 underflows its
// squared length, and normalize gives NaN). a, b must be non-zero; a scene scaled by a power of
// two gives the very same bits.
MCL_INLINE float mcl_max_abs3(float3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }
MCL_INLINE float3 scaled_cross(float3 a, float3 b) {
  return cross(a * (1.0f / mcl_max_abs3(a)), b * (1.0f / mcl_max_abs3(b)));
}
// Unit normal of the triangle with edges e1, e2 (the direction of cross(e1, e2)), at any scale.
MCL_INLINE float3 triangle_unit_normal(float3 e1, float3 e2) { return normalize(scaled_cross(e1, e2)); }
// Area of the triangle with edges e1, e2, at any scale the result itself can hold.
MCL_INLINE float triangle_area_of(float3 e1, float3 e2) {
  return 0.5f * length(scaled_cross(e1, e2)) * mcl_max_abs3(e1) * mcl_max_abs3(e2);
}
