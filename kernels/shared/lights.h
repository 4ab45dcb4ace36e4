// lights.h: area-light sampling for direct lighting: picking an emitter triangle from the CDF,
// a uniform point on it, converting its area pdf to solid angle, and the power heuristic. Pure;
// compiled by the kernels and by the host tests.
#pragma once
#include "geometry.h"

MCL_INLINE float luminance(float3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

MCL_INLINE uint triangle_material(MCL_GLOBAL const Triangle* t) { return as_uint(t->v0.w); }

MCL_INLINE float triangle_area(MCL_GLOBAL const Triangle* t) {
  return triangle_area_of(xyz(t->e1), xyz(t->e2));
}

// The guide table's bucket of u: floor(u * count), clamped to [0, count - 1] (a NaN: 0; its pick,
// count - 1 as the whole-table search finds it, lies outside that bucket's range, so pick_emitter
// searches the whole table for a NaN).
MCL_INLINE uint emitter_guide_bucket(uint count, float u) {
  float x = u * (float)count;
  uint b = x >= 1.0f ? (uint)fmin(x, (float)(count - 1u)) : 0u;
  return b;
}

// Tables at least this long are searched through their guide table (shorter ones whole: a few
// steps cost less than reading the guide).
#define MCL_EMITTER_GUIDE_MIN 16u

// The first emitter in [lo, hi] whose cdf exceeds u (hi if none): the binary search itself.
MCL_INLINE uint pick_emitter_between(MCL_GLOBAL const Emitter* emitters, uint lo, uint hi, float u) {
  while (lo < hi) {
    uint mid = (lo + hi) / 2;
    if (emitters[mid].cdf > u) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

// Index of the first emitter whose cdf exceeds u (count - 1 if none); count > 0. A binary search
// inside the range the guide table gives u's bucket: the pick of a bucket's smallest u up to the
// next bucket's (Emitter::guide; the same answer as a search of the whole table, as the pick
// grows with u), so a scene with many emitters takes one or two steps instead of log2(count).
MCL_INLINE uint pick_emitter(MCL_GLOBAL const Emitter* emitters, uint count, float u) {
  uint lo = 0u, hi = count - 1u;
  if (count >= MCL_EMITTER_GUIDE_MIN && !isnan(u)) {
    uint b = emitter_guide_bucket(count, u);
    lo = emitters[b].guide;
    hi = b + 1u < count ? emitters[b + 1u].guide : count - 1u;
  }
  return pick_emitter_between(emitters, lo, hi, u);
}

// Probability of picking a triangle of this area and emission (same formula as the host table).
MCL_INLINE float emitter_pick_probability(float area, float3 emission, float emitterPower) {
  return area * luminance(emission) / emitterPower;
}

// Uniform point on the triangle (v0, v0 + e1, v0 + e2) from u1, u2 in [0, 1).
MCL_INLINE float3 sample_triangle(float3 v0, float3 e1, float3 e2, float u1, float u2) {
  float su = sqrt(u1);
  return v0 + e1 * (su * (1.0f - u2)) + e2 * (su * u2);
}

// Area pdf to solid angle at the receiver: p_w = p_A * r^2 / cos(theta_light).
MCL_INLINE float area_to_solid_angle(float pdfArea, float dist2, float cosLight) {
  return pdfArea * dist2 / cosLight;
}

// Veach's power heuristic (beta = 2) for nf samples of pdf fPdf against ng samples of gPdf. The
// squares overflow for pdfs above ~1.8e19 (an emitter of area ~1e-19 seen from ~1 away): inf / inf
// would be NaN, so there the same weight comes from the ratio, 1 / (1 + (g / f)^2). Below that the
// operations are the plain formula's (the images of ordinary scenes keep their bits).
MCL_INLINE float power_heuristic(float nf, float fPdf, float ng, float gPdf) {
  float f = nf * fPdf, g = ng * gPdf;
  float sum = f * f + g * g;
  float r = g / f;
  return sum < INFINITY ? (f * f) / sum : 1.0f / (1.0f + r * r);
}
