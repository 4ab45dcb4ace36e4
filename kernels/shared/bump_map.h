// bump_map.h: height-map bump mapping of a hit: reads the material's bump texture (Material::maps.w,
// one more than its index, 0: none; texels hold the height gradient per unit of UV times the
// material's scale, (s dh/du, s dh/dv), made by the host, host/texture/bump_gradient.cpp), the
// triangle's UVs and edges, and gives the perturbed shading normal of a frame. Pure;
// compiled by the kernels, the host backend and the host tests.
#pragma once
#include "normal_map.h"

// The bumped unit normal of a triangle with edges e1 = v1 - v0, e2 = v2 - v0 and UV deltas
// (du1, dv1), (du2, dv2) of v1, v2 from v0, about the unit normal N (the unoriented shading
// normal), for the displacement gradient (gu, gv) = (dd/du, dd/dv). pbrt's bump mapping: the
// surface displaced by d along N has dP/du' = dP/du + gu N, dP/dv' = dP/dv + gv N, and
// n = normalize(cross(dP/du', dP/dv')) on N's side. dP/du and dP/dv (solved from the edges and UV
// deltas) are first made orthogonal to N, so a zero gradient gives N itself on smooth-shaded
// meshes too; both are kept multiplied by the UV determinant (no division: the cross product's
// direction is the same). The zero vector when the UVs are degenerate or the result is no usable
// direction.
// Written once for floats and lanes (the parameters as MCL_DEFINE_NORMAL_MAP's).
#define MCL_DEFINE_BUMP_NORMAL(P, F, F3, M, V)                                                             \
  MCL_INLINE F3 P##bump_normal(F3 N, F3 e1, F3 e2, F du1, F dv1, F du2, F dv2, F gu, F gv) {               \
    F det = du1 * dv2 - du2 * dv1;                                                                         \
    F3 T = V##_sub(V##_scale(e1, dv2), V##_scale(e2, dv1)); /* det dP/du */                                \
    F3 B = V##_sub(V##_scale(e2, du1), V##_scale(e1, du2)); /* det dP/dv */                                \
    T = V##_sub(T, V##_scale(N, V##_dot(N, T)));                                                           \
    B = V##_sub(B, V##_scale(N, V##_dot(N, B)));                                                           \
    F3 n = V##_cross(V##_add(T, V##_scale(N, gu * det)), V##_add(B, V##_scale(N, gv * det)));              \
    n = V##_select(V##_dot(n, N) < 0.0f, V##_neg(n), n);                                                   \
    F nl2 = V##_dot(n, n);                                                                                 \
    n = V##_scale(n, 1.0f / sqrt(fmax(nl2, 1e-30f)));                                                      \
    M ok = (det != 0.0f) & (fabs(det) < INFINITY) & (nl2 > 1e-30f) & (nl2 < INFINITY);                     \
    return V##_select(ok, n, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                   \
  }
MCL_DEFINE_BUMP_NORMAL(, float, float3, int, f3)
