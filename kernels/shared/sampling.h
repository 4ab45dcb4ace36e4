// sampling.h: hemisphere warps with their pdfs side by side (solid-angle measure), and an
// orthonormal basis around a normal. Pure; tested on the host with chi-square tests.
#pragma once
#include "compat.h"
#include "trig.h"

#define MCL_PI 3.14159265358979323846f
#define MCL_INV_PI 0.31830988618379067154f
#define MCL_INV_2PI 0.15915494309189533577f

// Every warp takes its angle's sine and cosine from the portable mcl_sincos_turns (trig.h, + and
// x only), never the built-in sin/cos: their last bit differs between devices and libm, and a
// last-bit change of a direction can change a whole path (or a hit near an edge).

// Uniform over the hemisphere z >= 0: p(w) = 1 / (2 pi).
MCL_INLINE float3 sample_uniform_hemisphere(float u1, float u2) {
  float z = u1;
  float r = sqrt(fmax(0.0f, 1.0f - z * z));
  float s, c;
  mcl_sincos_turns(u2, &s, &c);
  return make_float3(r * c, r * s, z);
}
MCL_INLINE float pdf_uniform_hemisphere(void) { return MCL_INV_2PI; }

// Cosine-weighted over the hemisphere z >= 0 (Malley: uniform disk lifted): p(w) = cos(theta) / pi.
MCL_INLINE float3 sample_cosine_hemisphere(float u1, float u2) {
  float r = sqrt(u1);
  float s, c;
  mcl_sincos_turns(u2, &s, &c);
  float z = sqrt(fmax(0.0f, 1.0f - u1));
  return make_float3(r * c, r * s, z);
}
// Written once for a float type F (float here; the packet stages' vfloat lanes, stage_lanes.h).
#define MCL_DEFINE_PDF_COSINE_HEMISPHERE(name, F) \
  MCL_INLINE F name(F cosTheta) { return fmax(cosTheta, (F)(0.0f)) * MCL_INV_PI; }
MCL_DEFINE_PDF_COSINE_HEMISPHERE(pdf_cosine_hemisphere, float)

// Uniform on the unit disk (Shirley and Chiu's concentric map): p = 1 / pi per unit area.
MCL_INLINE float2 sample_concentric_disk(float u1, float u2) {
  float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  if (a == 0.0f && b == 0.0f) return make_float2(0.0f, 0.0f);
  if (fabs(a) > fabs(b)) {  // phi = pi/4 (b / a), |phi| <= pi/4
    float2 sc = mcl_sincos_poly((MCL_PI / 4.0f) * (b / a));
    return make_float2(a * sc.y, a * sc.x);
  }
  // phi = pi/2 - t, t = pi/4 (a / b): cos(phi) = sin(t), sin(phi) = cos(t)
  float2 sc = mcl_sincos_poly((MCL_PI / 4.0f) * (a / b));
  return make_float2(b * sc.x, b * sc.y);
}

// Tangent frame (t, b, n) for a unit normal n, branchless and continuous except at n.z = -1
// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
MCL_INLINE void make_basis(float3 n, float3* t, float3* b) {
  float s = copysign(1.0f, n.z);
  float a = -1.0f / (s + n.z);
  float c = n.x * n.y * a;
  *t = make_float3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  *b = make_float3(c, s + n.y * n.y * a, -n.y);
}

// Direction in the local frame (z along n) to world space.
MCL_INLINE float3 to_world(float3 dirLocal, float3 n) {
  float3 t, b;
  make_basis(n, &t, &b);
  return t * dirLocal.x + b * dirLocal.y + n * dirLocal.z;
}
