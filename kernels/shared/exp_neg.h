// exp_neg.h: exp(-x) for x >= 0 from + - * only, the same bits on every device and on the host
// (the built-in exp's last bit differs between devices and libm). Pure; compiled by the kernels and
// the host tests.
#pragma once
#include "compat.h"

// exp(-x) for x >= 0 with + - * only (the built-in exp differs between devices): 2^-n by the
// exponent bits, and e^-t for t = the rest in [0, ln 2) by its Taylor series to t^9 (relative
// error below 2e-8).
MCL_INLINE float mcl_exp_neg(float x) {
  float y = fmin(x * 1.44269504f, 200.0f);  // past 126 the result is 0; the cast stays in range (NaN: 200)
  int n = (int)y;
  float t = (y - (float)n) * 0.693147181f;
  float p = 1.0f - t * (1.0f - t * (0.5f - t * (1.0f / 6.0f - t * (1.0f / 24.0f - t * (1.0f / 120.0f - t * (1.0f / 720.0f - t * (1.0f / 5040.0f - t * (1.0f / 40320.0f - t * (1.0f / 362880.0f)))))))));
  float scale = as_float((uint)(127 - (n < 126 ? n : 126)) << 23);
  return n >= 126 ? 0.0f : p * scale;
}
