// ffloat.h: float-float ("double-float") sums: a value kept as the unevaluated sum hi + lo of two
// floats (|lo| <= ulp(hi) / 2, about 48 bits of significand) from float operations only (OpenCL C
// 1.2 kernels have no doubles), on the lanes' vfloat (shared/lanes.h: a float at W = 1, each lane
// independent). Knuth's two-sum: exact as long as no FMA is contracted in (the kernels set
// FP_CONTRACT OFF, the host compiles with -ffp-contract=off). Pure; compiled by the kernels and by
// the host backend.
#pragma once
#include "lanes.h"

typedef struct {
  vfloat hi, lo;
} vffloat;

MCL_INLINE vffloat ff_make(vfloat hi, vfloat lo) {
  vffloat r;
  r.hi = hi;
  r.lo = lo;
  return r;
}

// s + e == a + b exactly, s = fl(a + b).
MCL_INLINE vffloat ff_two_sum(vfloat a, vfloat b) {
  vfloat s = a + b;
  vfloat v = s - a;
  return ff_make(s, (a - (s - v)) + (b - v));
}

// x + t, for a float t: the rounding error of hi + t goes into lo, which is then folded back.
MCL_INLINE vffloat ff_add_float(vffloat x, vfloat t) {
  vffloat s = ff_two_sum(x.hi, t);
  return ff_two_sum(s.hi, s.lo + x.lo);
}

// t where m is set, f elsewhere.
MCL_INLINE vffloat ff_select(vmask m, vffloat t, vffloat f) { return ff_make(vsel(m, t.hi, f.hi), vsel(m, t.lo, f.lo)); }
