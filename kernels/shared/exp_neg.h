// exp_neg.h: exp(-x) for x >= 0 from + - * only, the same bits on every device and on the host
// (the built-in exp's last bit differs between devices and libm). Pure; compiled by the kernels and
// the host tests.
#pragma once
#include "lanes.h"  // vsel: a select for scalars and lanes alike

// exp(-x) for x >= 0 with + - * only (the built-in exp differs between devices): 2^-n by the
// exponent bits, and e^-t for t = the rest in [0, ln 2) by its Taylor series to t^9 (relative
// error below 2e-8). Written once for a float type F and its int type I (float, int here; the
// packet stages' vfloat, vint in stages/lane_bsdf.h) with the conversions F -> I, I -> F and the bit
// casts I -> uint, uint -> F.
#define MCL_DEFINE_EXP_NEG(P, F, I, CVT_I_F, CVT_F_I, I_AS_U, AS_F)                                     \
  MCL_INLINE F P##exp_neg(F x) {                                                                        \
    F y = fmin(x * 1.44269504f, 200.0f); /* past 126 the result is 0; the cast stays in range (NaN: 200) */ \
    I n = CVT_I_F(y);                                                                                   \
    F t = (y - CVT_F_I(n)) * 0.693147181f;                                                              \
    F p = 1.0f - t * (1.0f - t * (0.5f - t * (1.0f / 6.0f - t * (1.0f / 24.0f - t * (1.0f / 120.0f - t * (1.0f / 720.0f - t * (1.0f / 5040.0f - t * (1.0f / 40320.0f - t * (1.0f / 362880.0f))))))))); \
    F scale = AS_F(I_AS_U((I)(127) - vsel(n < 126, n, (I)(126))) << 23);                                \
    return vsel(n >= 126, (F)(0.0f), p * scale);                                                        \
  }
MCL_DEFINE_EXP_NEG(mcl_, float, int, (int), (float), (uint), as_float)
