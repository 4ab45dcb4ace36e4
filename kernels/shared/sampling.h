// sampling.h: hemisphere warps with their pdfs side by side (solid-angle measure), and an
// orthonormal basis around a normal. Pure; tested on the host with chi-square tests.
#pragma once
#include "lanes.h"
#include "trig.h"

#define MCL_PI 3.14159265358979323846f
#define MCL_INV_PI 0.31830988618379067154f
#define MCL_INV_2PI 0.15915494309189533577f

// Every warp takes its angle's sine and cosine from the portable sincos_turns (trig.h, + and
// x only), never the built-in sin/cos: their last bit differs between devices and libm, and a
// last-bit change of a direction can change a whole path (or a hit near an edge).

// The warps are written once for a float type F, its 3-vector F3 and that vector's operations V, with
// trig.h's sine and cosine of prefix S (float, float3, f3, mcl_ here; the packet stages' vfloat,
// vfloat3, v3, v_ in stage_lanes.h, shared/lanes.h),
// so each lane rounds the scalar function's operations in the same order. Selects (vsel), not
// branches: a lane computes both sides and keeps one, the same bits as the branch it would take.
// - sample_uniform_hemisphere: uniform over the hemisphere z >= 0, p(w) = 1 / (2 pi).
// - sample_cosine_hemisphere: cosine-weighted (Malley: uniform disk lifted), p(w) = cos(theta) / pi.
// - sample_concentric_disk: uniform on the unit disk (Shirley and Chiu's concentric map), p = 1 / pi
//   per unit area; phi = pi/4 (b / a) where |a| > |b|, else pi/2 - pi/4 (a / b).
// - make_basis: the tangent frame (t, b, n) of a unit normal n, branchless and continuous except at
//   n.z = -1 (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017); to_world: a
//   direction in the local frame (z along n) to world space.
#define MCL_DEFINE_WARPS(P, S, F, F3, V)                                                        \
  MCL_INLINE F3 P##sample_uniform_hemisphere(F u1, F u2) {                                     \
    F z = u1;                                                                                  \
    F r = sqrt(fmax((F)(0.0f), 1.0f - z * z));                                                 \
    F s, c;                                                                                    \
    S##sincos_turns(u2, &s, &c);                                                               \
    return V##_make(r * c, r * s, z);                                                          \
  }                                                                                            \
  MCL_INLINE F3 P##sample_cosine_hemisphere(F u1, F u2) {                                      \
    F r = sqrt(u1);                                                                            \
    F s, c;                                                                                    \
    S##sincos_turns(u2, &s, &c);                                                               \
    F z = sqrt(fmax((F)(0.0f), 1.0f - u1));                                                    \
    return V##_make(r * c, r * s, z);                                                          \
  }                                                                                            \
  MCL_INLINE F P##pdf_cosine_hemisphere(F cosTheta) { return fmax(cosTheta, (F)(0.0f)) * MCL_INV_PI; } \
  MCL_INLINE void P##concentric_disk(F u1, F u2, F* x, F* y) {                                 \
    F a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;                                              \
    F sn, cs;                                                                                  \
    S##sincos_poly(vsel(fabs(a) > fabs(b), (MCL_PI / 4.0f) * (b / a), (MCL_PI / 4.0f) * (a / b)), &sn, &cs); \
    *x = vsel(fabs(a) > fabs(b), a * cs, b * sn);                                              \
    *y = vsel(fabs(a) > fabs(b), a * sn, b * cs);                                              \
    *x = vsel((a == 0.0f) & (b == 0.0f), (F)(0.0f), *x);                                          \
    *y = vsel((a == 0.0f) & (b == 0.0f), (F)(0.0f), *y);                                          \
  }                                                                                            \
  MCL_INLINE void P##make_basis(F3 n, F3* t, F3* b) {                                          \
    F s = copysign((F)(1.0f), n.z);                                                            \
    F a = -1.0f / (s + n.z);                                                                   \
    F c = n.x * n.y * a;                                                                       \
    *t = V##_make(1.0f + s * n.x * n.x * a, s * c, -s * n.x);                                  \
    *b = V##_make(c, s + n.y * n.y * a, -n.y);                                                 \
  }                                                                                            \
  MCL_INLINE F3 P##to_world(F3 dirLocal, F3 n) {                                               \
    F3 t, b;                                                                                   \
    P##make_basis(n, &t, &b);                                                                  \
    return V##_add(V##_add(V##_scale(t, dirLocal.x), V##_scale(b, dirLocal.y)), V##_scale(n, dirLocal.z)); \
  }
MCL_DEFINE_WARPS(, mcl_, float, float3, f3)
MCL_INLINE float pdf_uniform_hemisphere(void) { return MCL_INV_2PI; }
MCL_INLINE float2 sample_concentric_disk(float u1, float u2) {
  float x, y;
  concentric_disk(u1, u2, &x, &y);
  return make_float2(x, y);
}
