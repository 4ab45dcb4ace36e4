// trig.h: sine and cosine of 2 pi t from additions and multiplications only, so the same inputs
// give the same bits on every device (OpenCL lets sin/cos differ by a few ulp, and PoCL's
// vectorised ones differ from glibc's in the last bit). Used by the environment and GGX samplers,
// the portable cosine hemisphere and the concentric disk (sampling.h): the one portable sin/cos.
// t is reduced to within 1/8 turn of the nearest quarter turn, then Taylor polynomials (error
// < 3e-8 on [-pi/4, pi/4]). Pure; compiled by the kernels and by the host tests.
#pragma once
#include "lanes.h"  // vsel: a select for scalars and lanes alike

// Written once for a float type F, its int type I and C's float -> int conversion CVT_I (float, int
// here; the packet stages' vfloat, vint, v_cvt_i_f in stage_lanes.h), so each lane rounds the
// scalar function's operations (vsel: the select of shared/lanes.h).
// sincos_poly: (sin x, cos x) for x in [-pi/4, pi/4] by Taylor polynomials, written out so that
// every device rounds the same operations (error below 3e-8). sincos_turns: of 2 pi t.
#define MCL_DEFINE_SINCOS(P, F, I, CVT_I)                                                                   \
  MCL_INLINE void P##sincos_poly(F x, F* sn, F* cs) {                                                       \
    F x2 = x * x;                                                                                           \
    *sn = x * (1.0f + x2 * (-1.6666667e-1f + x2 * (8.3333333e-3f + x2 * (-1.9841270e-4f + x2 * 2.7557319e-6f)))); \
    *cs = 1.0f + x2 * (-0.5f + x2 * (4.1666667e-2f + x2 * (-1.3888889e-3f + x2 * (2.4801587e-5f + x2 * -2.7557319e-7f)))); \
  }                                                                                                         \
  MCL_INLINE void P##sincos_turns(F t, F* s, F* c) {                                                        \
    F q = floor(t * 4.0f + 0.5f);                                                                           \
    F sn, cs;                                                                                               \
    P##sincos_poly((t - q * 0.25f) * 6.28318530717958647692f, &sn, &cs); /* in [-pi/4, pi/4] */             \
    I k = CVT_I(q) & 3;                                                                                     \
    *s = vsel(k == 0, sn, vsel(k == 1, cs, vsel(k == 2, -sn, -cs)));                                        \
    *c = vsel(k == 0, cs, vsel(k == 1, -sn, vsel(k == 2, -cs, sn)));                                        \
  }
MCL_DEFINE_SINCOS(mcl_, float, int, (int))

// acos(x) for x in [-1, 1] from a polynomial and one sqrt (Abramowitz and Stegun 4.4.46, error
// below 2e-8 rad on [0, 1]; acos(-x) = pi - acos(x)), so every device gets the same bits (the
// spot light's falloff). Branch-free: selects only.
// Written once for floats and lanes (P, F: mcl_, float here; v_, vfloat in stages/stage_lanes.h).
#define MCL_DEFINE_ACOS(P, F)                                                                                  \
  MCL_INLINE F P##acos(F x) {                                                                                  \
    F a = fmin(fabs(x), 1.0f);                                                                                 \
    F p = 1.5707963050f +                                                                                      \
          a * (-0.2145988016f +                                                                                \
               a * (0.0889789874f +                                                                            \
                    a * (-0.0501743046f +                                                                      \
                         a * (0.0308918810f + a * (-0.0170881256f + a * (0.0066700901f + a * -0.0012624911f)))))); \
    F r = sqrt(1.0f - a) * p;                                                                                  \
    return vsel(x < 0.0f, 3.14159265358979323846f - r, r);                                                     \
  }
MCL_DEFINE_ACOS(mcl_, float)

// atan2(y, x) from a polynomial and one division (Abramowitz and Stegun 4.4.49 for atan on [0, 1],
// error below 2e-8 rad; the octant folded back by selects), so every device gets the same bits
// (the environment map's longitude). Signed zeros as IEEE's atan2: atan2(+-0, -0) = +-pi, from the
// sign bits (AS_U: the float's bits). Written once for floats and lanes (P, F, U, AS_U: mcl_,
// float, uint, as_uint here; v_, vfloat, vuint, v_as_uint in stages/lane_lights.h).
#define MCL_DEFINE_ATAN2(P, F, U, AS_U)                                                                       \
  MCL_INLINE F P##atan2(F y, F x) {                                                                           \
    F ay = fabs(y), ax = fabs(x);                                                                             \
    F hi = fmax(ay, ax), lo = fmin(ay, ax);                                                                   \
    F a = vsel(hi > 0.0f, lo / hi, (F)(0.0f));                                                                \
    F a2 = a * a;                                                                                             \
    F r = a * (1.0f +                                                                                         \
               a2 * (-0.3333314528f +                                                                         \
                     a2 * (0.1999355085f +                                                                    \
                           a2 * (-0.1420889944f +                                                             \
                                 a2 * (0.1065626393f +                                                        \
                                       a2 * (-0.0752896400f +                                                 \
                                             a2 * (0.0429096138f + a2 * (-0.0161657367f + a2 * 0.0028662257f)))))))); \
    r = vsel(ay > ax, 1.57079632679489661923f - r, r);                                                        \
    r = vsel((AS_U(x) >> 31) != 0u, 3.14159265358979323846f - r, r);                                          \
    return vsel((AS_U(y) >> 31) != 0u, -r, r);                                                                \
  }
MCL_DEFINE_ATAN2(mcl_, float, uint, as_uint)
