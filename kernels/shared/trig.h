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

// acos(x) for x in [-1, 1] from a polynomial and one sqrt (Abramowitz and Stegun 4.4.46, error
// below 2e-8 rad on [0, 1]; acos(-x) = pi - acos(x)), so every device gets the same bits (the
// spot light's falloff). Branch-free: selects only.
MCL_INLINE float mcl_acos(float x) {
  float a = fmin(fabs(x), 1.0f);
  float p = 1.5707963050f +
            a * (-0.2145988016f +
                 a * (0.0889789874f +
                      a * (-0.0501743046f +
                           a * (0.0308918810f + a * (-0.0170881256f + a * (0.0066700901f + a * -0.0012624911f))))));
  float r = sqrt(1.0f - a) * p;
  return x < 0.0f ? 3.14159265358979323846f - r : r;
}
