// lights.h: what light sampling shares: picking an emitter triangle from the CDF (through its
// guide table), a uniform point on a triangle, luminance and the power heuristic (the area pdf in
// solid angle: light_area.h). Pure; compiled by the kernels and by the host tests.
#pragma once
#include "geometry.h"

MCL_INLINE uint triangle_material(MCL_GLOBAL const Triangle* t) { return as_uint(t->v0.w); }

MCL_INLINE float triangle_area(MCL_GLOBAL const Triangle* t) {
  return triangle_area_of(xyz(t->e1), xyz(t->e2));
}

// Tables at least this long are searched through their guide table (shorter ones whole: a few
// steps cost less than reading the guide).
#define MCL_EMITTER_GUIDE_MIN 16u

// Written once for floats and lanes (P, F, F3, U, M, ANY, G, CVT_U_F, AS_U: the prefix, float,
// float3, uint, int mask, any, the table reads' prefix (mcl_gather_float), float to uint and a
// float's bits here; v_ and the lanes' in stages/stage_lanes.h; each lane does the float
// function's operations):
// - luminance: of a linear RGB colour (Rec. 709 weights).
// - power_heuristic_of: Veach's power heuristic (beta = 2) for the weights f = nf * fPdf and
//   g = ng * gPdf. The squares overflow for pdfs above ~1.8e19 (an emitter of area ~1e-19 seen from
//   ~1 away): inf / inf would be NaN, so there the same weight comes from the ratio,
//   1 / (1 + (g / f)^2). Below that the operations are the plain formula's.
// - emitter_guide_bucket: the guide table's bucket of u, floor(u * count), clamped to
//   [0, count - 1] (a NaN: 0; its pick, count - 1 as the whole-table search finds it, lies outside
//   that bucket's range, so pick_emitter searches the whole table for a NaN).
// - pick_emitter_between: the first emitter in [lo, hi] whose cdf exceeds u (hi if none): the
//   binary search itself, lanes masked as they finish.
// - pick_emitter: index of the first emitter whose cdf exceeds u (count - 1 if none); count > 0.
//   A binary search inside the range the guide table gives u's bucket: the pick of a bucket's
//   smallest u up to the next bucket's (Emitter::guide; the same answer as a search of the whole
//   table, as the pick grows with u), so a scene with many emitters takes one or two steps
//   instead of log2(count).
#define MCL_DEFINE_LIGHT_PICKS(P, F, F3, U, M, ANY, G, CVT_U_F, AS_U)                                        \
  MCL_INLINE F P##luminance(F3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }                  \
  MCL_INLINE F P##power_heuristic_of(F f, F g) {                                                             \
    F sum = f * f + g * g;                                                                                   \
    F r = g / f;                                                                                             \
    return vsel(sum < INFINITY, (f * f) / sum, 1.0f / (1.0f + r * r));                                      \
  }                                                                                                          \
  MCL_INLINE U P##emitter_guide_bucket(uint count, F u) {                                                    \
    F x = u * (float)count;                                                                                  \
    return vsel(x >= 1.0f, CVT_U_F(fmin(x, (float)(count - 1u))), (U)(0u));                                 \
  }                                                                                                          \
  MCL_INLINE U P##pick_emitter_between(MCL_GLOBAL const Emitter* emitters, U lo, U hi, F u) {                \
    MCL_GLOBAL const float* cdf = (MCL_GLOBAL const float*)emitters + 1; /* Emitter::cdf */                  \
    for (;;) {                                                                                               \
      M on = lo < hi;                                                                                        \
      if (!ANY(on)) break;                                                                                   \
      U mid = (lo + hi) / 2u;                                                                                \
      M above = G##gather_float(cdf, vsel(on, mid, lo), 4u) > u;                                             \
      hi = vsel(on & above, mid, hi);                                                                        \
      lo = vsel(on & (above == (M)(0)), mid + 1u, lo);                                                       \
    }                                                                                                        \
    return lo;                                                                                               \
  }                                                                                                          \
  MCL_INLINE U P##pick_emitter(MCL_GLOBAL const Emitter* emitters, uint count, F u) {                        \
    U lo = (U)(0u), hi = (U)(count - 1u);                                                                    \
    if (count >= MCL_EMITTER_GUIDE_MIN) {                                                                    \
      MCL_GLOBAL const float* guide = (MCL_GLOBAL const float*)emitters + 3; /* Emitter::guide's bits */     \
      U b = P##emitter_guide_bucket(count, u);                                                               \
      M inner = b + 1u < count, nan = isnan(u);                                                              \
      lo = vsel(nan, lo, AS_U(G##gather_float(guide, b, 4u)));                                               \
      hi = vsel(nan | (inner == (M)(0)), hi, AS_U(G##gather_float(guide, vsel(inner, b + 1u, b), 4u)));      \
    }                                                                                                        \
    return P##pick_emitter_between(emitters, lo, hi, u);                                                     \
  }
MCL_DEFINE_LIGHT_PICKS(, float, float3, uint, int, MCL_ANY1, mcl_, (uint), as_uint)

// Uniform point on the triangle (v0, v0 + e1, v0 + e2) from u1, u2 in [0, 1).
MCL_INLINE float3 sample_triangle(float3 v0, float3 e1, float3 e2, float u1, float u2) {
  float su = sqrt(u1);
  return v0 + e1 * (su * (1.0f - u2)) + e2 * (su * u2);
}

// Veach's power heuristic (beta = 2) for nf samples of pdf fPdf against ng samples of gPdf
// (power_heuristic_of).
MCL_INLINE float power_heuristic(float nf, float fPdf, float ng, float gPdf) {
  return power_heuristic_of(nf * fPdf, ng * gPdf);
}
