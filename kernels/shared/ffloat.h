// ffloat.h: float-float ("double-float") arithmetic on float4 lanes: a value is an unevaluated
// sum hi + lo of two floats with |lo| <= ulp(hi) / 2, about 48 bits of significand, from float
// operations only (OpenCL C 1.2 kernels have no doubles). Knuth's two-sum and Dekker's splitting
// product, so no FMA is needed — and none may be contracted in: the kernels set FP_CONTRACT OFF
// and the host compiles with -ffp-contract=off. Every lane is independent; the w lanes compute
// like the others. Pure; compiled by the kernels and by the host tests.
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

// s + e == a + b exactly (s = fl(a + b)).
MCL_INLINE ffloat4 ff_two_sum(float4 a, float4 b) {
  float4 s = a + b;
  float4 v = s - a;
  return ff_make(s, (a - (s - v)) + (b - v));
}

// As ff_two_sum, for |a| >= |b| (or a == 0).
MCL_INLINE ffloat4 ff_fast_two_sum(float4 a, float4 b) {
  float4 s = a + b;
  return ff_make(s, b - (s - a));
}

// Dekker's split of a into hi + lo, each with at most 12 significant bits.
MCL_INLINE ffloat4 ff_split(float4 a) {
  float4 c = a * 4097.0f;  // 2^12 + 1
  float4 hi = c - (c - a);
  return ff_make(hi, a - hi);
}

// p + e == a * b exactly (p = fl(a * b)), barring overflow.
MCL_INLINE ffloat4 ff_two_prod(float4 a, float4 b) {
  float4 p = a * b;
  ffloat4 as = ff_split(a), bs = ff_split(b);
  float4 e = ((as.hi * bs.hi - p) + as.hi * bs.lo + as.lo * bs.hi) + as.lo * bs.lo;
  return ff_make(p, e);
}

MCL_INLINE ffloat4 ff_add(ffloat4 x, ffloat4 y) {
  ffloat4 s = ff_two_sum(x.hi, y.hi);
  ffloat4 t = ff_two_sum(x.lo, y.lo);
  float4 e = s.lo + t.hi;
  s = ff_fast_two_sum(s.hi, e);
  return ff_fast_two_sum(s.hi, s.lo + t.lo);
}

MCL_INLINE ffloat4 ff_neg(ffloat4 x) { return ff_make(-x.hi, -x.lo); }

MCL_INLINE ffloat4 ff_mul(ffloat4 x, ffloat4 y) {
  ffloat4 p = ff_two_prod(x.hi, y.hi);
  float4 e = p.lo + (x.hi * y.lo + x.lo * y.hi);
  return ff_fast_two_sum(p.hi, e);
}

// x / y with two quotient corrections.
MCL_INLINE ffloat4 ff_div(ffloat4 x, ffloat4 y) {
  float4 q1 = x.hi / y.hi;
  ffloat4 r = ff_add(x, ff_neg(ff_mul(ff_make(q1, make_float4(0.0f, 0.0f, 0.0f, 0.0f)), y)));
  float4 q2 = r.hi / y.hi;
  return ff_fast_two_sum(q1, q2);
}

// The unsigned 64-bit count n < 2^48 in every lane, exactly: its top and bottom 24 bits are each
// a float, and their sum is renormalised.
MCL_INLINE ffloat4 ff_from_count(ulong n) {
  float hi = (float)(n & 0xffffff000000ul);
  float lo = (float)(n & 0xfffffful);
  return ff_fast_two_sum(make_float4(hi, hi, hi, hi), make_float4(lo, lo, lo, lo));
}
