// normal_map.h: the tangent-space normal map of a hit: reads the material's normal texture
// (Material::maps.z, one more than its index, 0: none; texels hold the decoded tangent-space
// vector ((2r - 1) s, (2g - 1) s, 2b - 1), s the map's scale, baked in by the host), the triangle's
// corner tangents (glTF TANGENT, MCL_ATTR_TANGENTS) or else its UVs and edges, and gives the
// perturbed shading normal of a frame (lane_frame, stages/stage_lanes.h). Pure; compiled by the kernels, the host backend and
// the host tests.
#pragma once
#include "shading.h"
#include "surface_texture.h"

// The relief maps' functions written once for floats and lanes (P, F, F3, F4, M, V, MAKE4, FR: the
// prefix, float, float3, float4, int mask, f3, make_float4, SurfaceFrame here; the packet stages'
// v_, vfloat, vfloat3, vfloat4, vmask, v3, v4_make, LaneFrame in stages/stage_lanes.h).
// - frame_mapped_normal: the frame's part both tangent sources share: T made orthogonal to the
//   unit normal N (Gram-Schmidt) and unit, B = hand x cross(N, T), n = normalize(t.x T + t.y B +
//   t.z N); *ok set where T had a usable part across N and n is a usable direction.
// - tangent_to_world: the unit tangent-space normal t = (t.x, t.y, t.z) (t need not be unit) in
//   world space for a triangle with edges e1 = v1 - v0, e2 = v2 - v0 and UV deltas (du1, dv1),
//   (du2, dv2) of v1, v2 from v0, about the unit normal N (the unoriented shading normal).
//   MikkTSpace's rule on one triangle: T = dP/du made orthogonal to N (Gram-Schmidt), the
//   handedness sign = sign of dot(cross(N, dP/du), dP/dv), B = sign x cross(N, T) (glTF's bitangent
//   from a TANGENT with w = sign), n = normalize(t.x T + t.y B + t.z N). v runs up the image
//   (montecl's UVs; glTF's are flipped on reading), so green is +v, glTF's and OpenGL's convention.
//   The zero vector when the UVs are degenerate or the result is no usable direction.
// - file_tangent_to_world: t in world space from the file's tangents (glTF TANGENT): corner
//   tangents c0, c1, c2 (xyz unit, w the handedness +1 or -1) interpolated at barycentrics (u, v),
//   made orthogonal to N, B = sign x cross(N, T), n as above. sign is the majority of the three
//   corners' w: a triangle has one handedness, which a MikkTSpace exporter gives all three corners;
//   where a file's corners disagree the majority is the same whichever corner comes first (a
//   mirroring placement reorders corners). The zero vector when the tangents are no usable
//   direction there (zero, or along N).
// - normal_mapped_frame: the frame fr with its shading normal replaced by the mapped normal n
//   (about the unoriented normal N), put on ng's side by the sign that puts N there (so both faces
//   of a two-sided surface see the same relief). Unchanged (bit for bit) when t = (0, 0, z) (a flat
//   map), when n is the zero vector, or when n falls on or below the geometric surface (the
//   unmapped shading normal is kept: a mapped normal never points into the surface it shades).
// - map_uv_deltas_of: the UV deltas (du1, dv1, du2, dv2) of corners 1 and 2 from corner 0 in the
//   UVs of the map whose transform rows are row0, row1: a relief map's tangent frame follows the
//   map's own UVs, so its transform's linear part is applied to the deltas.
#define MCL_DEFINE_NORMAL_MAP(P, F, F3, F4, M, V, MAKE4, FR)                                             \
  MCL_INLINE F3 P##frame_mapped_normal(F3 N, F3 T, F hand, F3 t, M* ok) {                                 \
    F3 To = V##_sub(T, V##_scale(N, V##_dot(N, T)));                                                      \
    F tl2 = V##_dot(To, To);                                                                              \
    To = V##_scale(To, 1.0f / sqrt(fmax(tl2, 1e-30f)));                                                   \
    F3 Bo = V##_scale(V##_cross(N, To), hand);                                                            \
    F3 n = V##_add(V##_add(V##_scale(To, t.x), V##_scale(Bo, t.y)), V##_scale(N, t.z));                   \
    F nl2 = V##_dot(n, n);                                                                                \
    n = V##_scale(n, 1.0f / sqrt(fmax(nl2, 1e-30f)));                                                     \
    *ok = (tl2 > 1e-30f) & (tl2 < INFINITY) & (nl2 > 1e-20f) & (nl2 < INFINITY);                          \
    return n;                                                                                             \
  }                                                                                                       \
  MCL_INLINE F3 P##tangent_to_world(F3 N, F3 e1, F3 e2, F du1, F dv1, F du2, F dv2, F3 t) {               \
    F det = du1 * dv2 - du2 * dv1;                                                                        \
    F sd = vsel(det < 0.0f, (F)(-1.0f), (F)(1.0f));                                                       \
    F3 T = V##_scale(V##_sub(V##_scale(e1, dv2), V##_scale(e2, dv1)), sd); /* along dP/du (|det| dP/du) */ \
    F3 B = V##_scale(V##_sub(V##_scale(e2, du1), V##_scale(e1, du2)), sd); /* along dP/dv */              \
    F hand = vsel(V##_dot(V##_cross(N, T), B) < 0.0f, (F)(-1.0f), (F)(1.0f));                             \
    M ok;                                                                                                 \
    F3 n = P##frame_mapped_normal(N, T, hand, t, &ok);                                                    \
    ok = ok & (det != 0.0f) & (fabs(det) < INFINITY);                                                     \
    return V##_select(ok, n, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                  \
  }                                                                                                       \
  MCL_INLINE F3 P##file_tangent_to_world(F3 N, F4 c0, F4 c1, F4 c2, F u, F v, F3 t) {                     \
    F3 T = V##_add(V##_add(V##_scale(V##_make(c0.x, c0.y, c0.z), 1.0f - u - v), V##_scale(V##_make(c1.x, c1.y, c1.z), u)), \
                   V##_scale(V##_make(c2.x, c2.y, c2.z), v));                                             \
    F sign = vsel(c0.w + c1.w + c2.w < 0.0f, (F)(-1.0f), (F)(1.0f));                                      \
    M ok;                                                                                                 \
    F3 n = P##frame_mapped_normal(N, T, sign, t, &ok);                                                    \
    return V##_select(ok, n, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                  \
  }                                                                                                       \
  MCL_INLINE FR P##normal_mapped_frame(FR fr, F3 N, F3 n, F3 t) {                                         \
    F3 no = V##_select(V##_dot(N, fr.ng) < 0.0f, V##_neg(n), n);                                          \
    M use = ((t.x != 0.0f) | (t.y != 0.0f)) & (V##_dot(no, fr.ng) > 0.0f);                                \
    FR s = fr;                                                                                            \
    s.ns = V##_select(use, no, fr.ns);                                                                    \
    s.smooth = use | fr.smooth;                                                                           \
    return s;                                                                                             \
  }                                                                                                       \
  MCL_INLINE F4 P##map_uv_deltas_of(F4 row0, F4 row1, F du1, F dv1, F du2, F dv2) {                       \
    return MAKE4(row0.x * du1 + row0.y * dv1, row1.x * du1 + row1.y * dv1, row0.x * du2 + row0.y * dv2,   \
                 row1.x * du2 + row1.y * dv2);                                                            \
  }
MCL_DEFINE_NORMAL_MAP(, float, float3, float4, int, f3, make_float4, SurfaceFrame)
