// shading.h: shading normals and the below-geometric-surface rule (no light leaks through a
// surface, no dark rings where shading and geometric normals disagree). Pure functions of
// their arguments; compiled by the kernels, the host backend and the host tests.
//
// At a hit, the geometric normal ng (the triangle's, flipped to face the incoming ray) keeps every
// geometric job: ray-origin offsets, emitter sides, and the side test below. The shading normal ns
// is the corner normals interpolated by barycentrics and normalised, flipped onto ng's side (so a
// file whose normals disagree with its winding shades the same); without normals ns = ng. The rule:
// - Cosines (Lambert, the AO estimator) are taken against ns; hemispheres (AO uniform and cosine,
//   BRDF sampling) are built around ns.
// - A direction below the geometric surface (dot(ng, w) <= 0) would leave through the surface:
//   a light or emitter direction there contributes zero (no light leaks through a surface).
// - A sampled direction that falls below the geometric surface is mirrored across the geometric
//   tangent plane (fold_above), so no sample is lost to the surface it left: a smooth convex object
//   in open space has AO exactly 1 (no dark rings at shading/geometry mismatch), and every ray that
//   is traced leaves above the surface (no leaks). The BRDF pdf is that of the folded lobe
//   (pdf_cosine_folded), so light and BRDF sampling estimate the same integral under MIS.
// SurfaceFrame bundles a hit's position, ng, ns and whether ns came from normals (`smooth`); the
// frame_* functions apply the rule, and reduce to the flat formulas exactly when smooth is 0, so
// scenes without normals render bit-identically to before.
#pragma once
#include "lanes.h"  // vsel: a select for scalars and lanes alike
#include "sampling.h"

typedef struct {
  float3 p;    // hit position (barycentric)
  float3 ng;   // geometric normal facing the incoming ray
  float3 ns;   // shading normal on ng's side (ng when the triangle has no normals)
  int smooth;  // 1 when ns came from the triangle's corner normals
  int backface;  // 1 when the ray arrived at the triangle's back face (the side opposite
                 // cross(v1 - v0, v2 - v0)): ng is then the triangle's normal negated. Kinds with
                 // an inside (dielectric) read it; 0 (the front, the outside) when unknown
} SurfaceFrame;

// Corner normals n0, n1, n2 at barycentrics (1 - u - v, u, v), normalised; the zero vector when the
// blend is no usable direction (zero, e.g. opposite corners, or non-finite). orient_to: ns flipped
// onto the side of ng. Written once for floats and lanes (V: f3 or v3).
#define MCL_DEFINE_INTERPOLATE_NORMAL(P, F, F3, V)                                                     \
  MCL_INLINE F3 P##interpolate_normal(F3 n0, F3 n1, F3 n2, F u, F v) {                                 \
    F3 n = V##_add(V##_add(V##_scale(n0, 1.0f - u - v), V##_scale(n1, u)), V##_scale(n2, v));          \
    F len2 = V##_dot(n, n);                                                                            \
    F3 unit = V##_scale(n, 1.0f / sqrt(len2));                                                         \
    return V##_select((len2 > 1e-20f) & (len2 < INFINITY), unit, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f))); \
  }                                                                                                    \
  MCL_INLINE F3 P##orient_to(F3 ns, F3 ng) { return V##_select(V##_dot(ns, ng) < 0.0f, V##_neg(ns), ns); }
MCL_DEFINE_INTERPOLATE_NORMAL(, float, float3, f3)

// 1 when w leaves above the geometric surface (strictly).
MCL_INLINE int above_surface(float3 ng, float3 w) { return dot(ng, w) > 0.0f; }

// The Lambert cosine for direction wi: dot(ns, wi), zero below the geometric surface or below ns.
MCL_INLINE float shading_cosine(float3 ns, float3 ng, float3 wi) {
  return above_surface(ng, wi) ? fmax(dot(ns, wi), 0.0f) : 0.0f;
}

// The rule's folding and the Lambertian lobe around a frame, written once for a float type F, its
// 3-vector F3 and mask M (float, float3, int here; the packet stages' vfloat, vfloat3, vmask in
// stage_lanes.h) with that type's dot, difference, scaling, select and constructor, so each lane
// does the scalar operations. For a flat frame ns is ng (surface_frame), so the smooth forms give
// the flat ones.
#define MCL_DEFINE_SHADING_RULE(P, F, F3, M, DOT, SUB, SCALE, SEL3, MAKE3, PDF)                        \
  /* w mirrored across the plane of ng when it points below it; unchanged otherwise. */                \
  MCL_INLINE F3 P##fold_above(F3 w, F3 ng) {                                                           \
    F d = DOT(w, ng);                                                                                  \
    return SEL3(d < 0.0f, SUB(w, SCALE(ng, 2.0f * d)), w);                                             \
  }                                                                                                    \
  /* Solid-angle pdf of wi under cosine sampling around ns folded above ng: the lobe's density at wi  \
     plus at wi's mirror image (which folding maps onto wi); zero below the geometric surface. */      \
  MCL_INLINE F P##pdf_cosine_folded(F3 ns, F3 ng, F3 wi) {                                             \
    F3 mirror = SUB(wi, SCALE(ng, 2.0f * DOT(wi, ng)));                                                \
    F r = PDF(DOT(ns, wi)) + PDF(DOT(ns, mirror));                                                     \
    return vsel(DOT(ng, wi) > 0.0f, r, (F)(0.0f));                                                     \
  }                                                                                                    \
  /* A Lambertian lobe of albedo kd: f cos = kd cos(ns, wi) / pi, zero below ns and, where smooth,     \
     below ng (diffuse_eval without a glossy lobe). */                                                 \
  MCL_INLINE F3 P##lambert_eval(F3 kd, F3 ng, F3 ns, M smooth, F3 wi) {                                \
    M above = (smooth == (M)(0)) | (DOT(ng, wi) > 0.0f);                                               \
    F c = DOT(ns, wi);                                                                                 \
    M lit = above & (c > 0.0f);                                                                        \
    F cpi = c * MCL_INV_PI;                                                                            \
    return MAKE3(vsel(lit, kd.x * cpi, (F)(0.0f)), vsel(lit, kd.y * cpi, (F)(0.0f)),                   \
                 vsel(lit, kd.z * cpi, (F)(0.0f)));                                                    \
  }                                                                                                    \
  /* Its pdf (diffuse_pdf without a glossy lobe): folded where smooth. */                              \
  MCL_INLINE F P##lambert_pdf(F3 ng, F3 ns, M smooth, F3 wi) {                                         \
    return vsel(smooth, P##pdf_cosine_folded(ns, ng, wi), PDF(DOT(ns, wi)));                           \
  }                                                                                                    \
  /* f cos / p of a Lambertian lobe of albedo 1 for a direction from its cosine sampling: 1 where      \
     flat; where smooth the shading cosine / (pi pdf), at most 1 (zero where the folded pdf is). */    \
  MCL_INLINE F P##cosine_weight(F3 ns, F3 ng, M smooth, F3 wi) {                                       \
    F pdf = P##pdf_cosine_folded(ns, ng, wi);                                                          \
    F c = vsel(DOT(ng, wi) > 0.0f, fmax(DOT(ns, wi), (F)(0.0f)), (F)(0.0f));                           \
    return vsel(smooth, vsel(pdf > 0.0f, c * MCL_INV_PI / pdf, (F)(0.0f)), (F)(1.0f));                 \
  }
MCL_INLINE float3 mcl_sub3(float3 a, float3 b) { return a - b; }
MCL_INLINE float3 mcl_scale3(float3 a, float s) { return a * s; }
MCL_DEFINE_SHADING_RULE(, float, float3, int, dot, mcl_sub3, mcl_scale3, MCL_SEL1, make_float3, pdf_cosine_hemisphere)

// --- the rule on a SurfaceFrame (smooth == 0: exactly the flat formulas) ---------------------

// A direction sampled in the local frame around ns (z along ns), in world space, folded above ng.
MCL_INLINE float3 frame_sample_direction(SurfaceFrame s, float3 dirLocal) {
  float3 w = to_world(dirLocal, s.ns);
  return s.smooth ? fold_above(w, s.ng) : w;
}
// The Lambert cosine of wi (may be <= 0 when flat: callers skip non-positive cosines).
MCL_INLINE float frame_cosine(SurfaceFrame s, float3 wi) {
  return s.smooth ? shading_cosine(s.ns, s.ng, wi) : dot(s.ng, wi);
}
