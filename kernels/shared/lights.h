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

// Index of the first emitter whose cdf exceeds u (binary search); count > 0.
MCL_INLINE uint pick_emitter(MCL_GLOBAL const Emitter* emitters, uint count, float u) {
  uint lo = 0, hi = count - 1;
  while (lo < hi) {
    uint mid = (lo + hi) / 2;
    if (emitters[mid].cdf > u) hi = mid;
    else lo = mid + 1;
  }
  return lo;
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
