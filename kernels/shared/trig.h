// trig.h: sine and cosine of 2 pi t from additions and multiplications only, so the same inputs
// give the same bits on every device (OpenCL lets sin/cos differ by a few ulp, and PoCL's
// vectorised ones differ from glibc's in the last bit). Used by the environment and GGX samplers,
// the portable cosine hemisphere and the concentric disk (sampling.h): the one portable sin/cos.
// t is reduced to within 1/8 turn of the nearest quarter turn, then Taylor polynomials (error
// < 3e-8 on [-pi/4, pi/4]). Pure; compiled by the kernels and by the host tests.
#pragma once
#include "compat.h"

// (sin x, cos x) for x in [-pi/4, pi/4] by Taylor polynomials, written out so that every device
// rounds the same operations (error below 3e-8).
MCL_INLINE float2 mcl_sincos_poly(float x) {
  float x2 = x * x;
  float sn = x * (1.0f + x2 * (-1.6666667e-1f + x2 * (8.3333333e-3f + x2 * (-1.9841270e-4f + x2 * 2.7557319e-6f))));
  float cs = 1.0f + x2 * (-0.5f + x2 * (4.1666667e-2f + x2 * (-1.3888889e-3f + x2 * (2.4801587e-5f + x2 * -2.7557319e-7f))));
  return make_float2(sn, cs);
}

MCL_INLINE void mcl_sincos_turns(float t, float* s, float* c) {
  float q = floor(t * 4.0f + 0.5f);
  float2 p = mcl_sincos_poly((t - q * 0.25f) * 6.28318530717958647692f);  // in [-pi/4, pi/4]
  float sn = p.x, cs = p.y;
  int k = ((int)q) & 3;
  *s = k == 0 ? sn : k == 1 ? cs : k == 2 ? -sn : -cs;
  *c = k == 0 ? cs : k == 1 ? -sn : k == 2 ? -cs : sn;
}
