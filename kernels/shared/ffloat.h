// ffloat.h: float-float ("double-float") sums on float4 lanes: a value kept as the unevaluated sum
// hi + lo of two floats (|lo| <= ulp(hi) / 2, about 48 bits of significand) from float operations
// only (OpenCL C 1.2 kernels have no doubles). Knuth's two-sum: exact as long as no FMA is
// contracted in (the kernels set FP_CONTRACT OFF, the host compiles with -ffp-contract=off).
// Every lane is independent. Pure; compiled by the kernels and by the host tests.
#pragma once
#include "compat.h"

typedef struct {
  float4 hi, lo;
} ffloat4;

MCL_INLINE ffloat4 ff_make(float4 hi, float4 lo) {
  ffloat4 r;
  r.hi = hi;
  r.lo = lo;
  return r;
}

// s + e == a + b exactly, s = fl(a + b).
MCL_INLINE ffloat4 ff_two_sum(float4 a, float4 b) {
  float4 s = a + b;
  float4 v = s - a;
  return ff_make(s, (a - (s - v)) + (b - v));
}

// x + t, for a float t: the rounding error of hi + t goes into lo, which is then folded back.
MCL_INLINE ffloat4 ff_add_float(ffloat4 x, float4 t) {
  ffloat4 s = ff_two_sum(x.hi, t);
  return ff_two_sum(s.hi, s.lo + x.lo);
}
