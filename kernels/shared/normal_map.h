// normal_map.h: the tangent-space normal map of a hit: reads the material's normal texture
// (Material::maps.z, one more than its index, 0: none; texels hold the decoded tangent-space
// vector ((2r - 1) s, (2g - 1) s, 2b - 1), s the map's scale, baked in by the host), the triangle's
// corner tangents (glTF TANGENT, MCL_ATTR_TANGENTS) or else its UVs and edges, and writes the
// perturbed shading normal of a SurfaceFrame. Pure; compiled by the kernels, the host backend and
// the host tests.
#pragma once
#include "shading.h"
#include "surface_texture.h"

// 1 when material m has a normal map.
MCL_INLINE int has_normal_map(Material m) { return as_uint(m.maps.z) != 0u; }

// The frame's part both tangent sources share: T made orthogonal to the unit normal N
// (Gram-Schmidt) and unit, B = hand x cross(N, T), n = normalize(t.x T + t.y B + t.z N); w 1 when
// T had a usable part across N and n is a usable direction, else 0.
MCL_INLINE float4 frame_mapped_normal(float3 N, float3 T, float hand, float3 t) {
  float3 To = T - N * dot(N, T);
  float tl2 = dot(To, To);
  To = To * (1.0f / sqrt(fmax(tl2, 1e-30f)));
  float3 Bo = cross(N, To) * hand;
  float3 n = To * t.x + Bo * t.y + N * t.z;
  float nl2 = dot(n, n);
  n = n * (1.0f / sqrt(fmax(nl2, 1e-30f)));
  int ok = tl2 > 1e-30f && tl2 < INFINITY && nl2 > 1e-20f && nl2 < INFINITY;
  return make_float4(n.x, n.y, n.z, ok ? 1.0f : 0.0f);
}

// The unit tangent-space normal t = (t.x, t.y, t.z) (t need not be unit) in world space for a
// triangle with edges e1 = v1 - v0, e2 = v2 - v0 and UV deltas (du1, dv1), (du2, dv2) of v1, v2
// from v0, about the unit normal N (the unoriented shading normal). MikkTSpace's rule on one
// triangle: T = dP/du made orthogonal to N (Gram-Schmidt), the handedness sign = sign of
// dot(cross(N, dP/du), dP/dv), B = sign x cross(N, T) (glTF's bitangent from a TANGENT with
// w = sign), n = normalize(t.x T + t.y B + t.z N). v runs up the image (montecl's UVs; glTF's are
// flipped on reading), so green is +v, glTF's and OpenGL's convention. The zero vector when the UVs
// are degenerate or the result is no usable direction.
MCL_INLINE float3 tangent_to_world(float3 N, float3 e1, float3 e2, float du1, float dv1, float du2, float dv2,
                                   float3 t) {
  float det = du1 * dv2 - du2 * dv1;
  float sd = det < 0.0f ? -1.0f : 1.0f;
  float3 T = (e1 * dv2 - e2 * dv1) * sd;  // along dP/du (|det| dP/du)
  float3 B = (e2 * du1 - e1 * du2) * sd;  // along dP/dv
  float hand = dot(cross(N, T), B) < 0.0f ? -1.0f : 1.0f;
  float4 n = frame_mapped_normal(N, T, hand, t);
  int ok = det != 0.0f && fabs(det) < INFINITY && n.w != 0.0f;
  return ok ? xyz(n) : make_float3(0.0f, 0.0f, 0.0f);
}

// The unit tangent-space normal t in world space from the file's tangents (glTF TANGENT): corner
// tangents c0, c1, c2 (xyz unit, w the handedness +1 or -1) interpolated at barycentrics (u, v),
// made orthogonal to the unit normal N (Gram-Schmidt), B = sign x cross(N, T) (glTF's bitangent),
// n = normalize(t.x T + t.y B + t.z N). sign is the majority of the three corners' w: a triangle has
// one handedness, which a MikkTSpace exporter gives all three corners; where a file's corners
// disagree the majority is the same whichever corner comes first (a mirroring placement reorders
// corners). The zero vector when the tangents are no usable direction there (zero, or along N).
MCL_INLINE float3 file_tangent_to_world(float3 N, float4 c0, float4 c1, float4 c2, float u, float v, float3 t) {
  float3 T = xyz(c0) * (1.0f - u - v) + xyz(c1) * u + xyz(c2) * v;
  float sign = c0.w + c1.w + c2.w < 0.0f ? -1.0f : 1.0f;
  float4 n = frame_mapped_normal(N, T, sign, t);
  return n.w != 0.0f ? xyz(n) : make_float3(0.0f, 0.0f, 0.0f);
}

// The frame fr with its shading normal replaced by the mapped normal n (tangent_to_world about the
// unoriented normal N), put on ng's side by the sign that puts N there (so both faces of a
// two-sided surface see the same relief). Unchanged (bit for bit) when t = (0, 0, z) (a flat map),
// when n is the zero vector, or when n falls on or below the geometric surface (the unmapped
// shading normal is kept: a mapped normal never points into the surface it shades).
MCL_INLINE SurfaceFrame normal_mapped_frame(SurfaceFrame fr, float3 N, float3 n, float3 t) {
  float3 no = dot(N, fr.ng) < 0.0f ? -n : n;
  int use = (t.x != 0.0f || t.y != 0.0f) && dot(no, fr.ng) > 0.0f;
  SurfaceFrame s = fr;
  s.ns = use ? no : fr.ns;
  s.smooth = use ? 1 : fr.smooth;
  return s;
}

// The normal that a relief map tilts at hit h on triangle tri (attributes sh, unit geometric
// normal ng0, unoriented): the interpolated corner normals, else ng0.
MCL_INLINE float3 unoriented_shading_normal(MCL_GLOBAL const Triangle* tri, MCL_GLOBAL const TriangleShading* sh,
                                            float3 ng0, Hit h) {
  float3 N = ng0;
  if (as_uint(tri->e2.w) & MCL_ATTR_NORMALS) {
    float3 ni = interpolate_normal(xyz(sh->n0), xyz(sh->n1), xyz(sh->n2), h.u, h.v);
    N = dot(ni, ni) > 0.0f ? ni : ng0;
  }
  return N;
}

// The UV deltas (du1, dv1, du2, dv2) of corners 1 and 2 from corner 0 (attributes sh) in the
// UVs of the map whose desc is d: a relief map's tangent frame follows the map's own UVs, so its
// transform's linear part is applied to the deltas.
MCL_INLINE float4 map_uv_deltas(TextureDesc d, MCL_GLOBAL const TriangleShading* sh) {
  float du1 = sh->n1.w - sh->n0.w, dv1 = sh->tv.y - sh->tv.x, du2 = sh->n2.w - sh->n0.w, dv2 = sh->tv.z - sh->tv.x;
  return make_float4(d.uvRow0.x * du1 + d.uvRow0.y * dv1, d.uvRow1.x * du1 + d.uvRow1.y * dv1,
                     d.uvRow0.x * du2 + d.uvRow0.y * dv2, d.uvRow1.x * du2 + d.uvRow1.y * dv2);
}

// The frame fr of hit h on triangle tri (attributes sh, unit geometric normal ng0, unoriented)
// under material m's normal map; fr unchanged without a map or without UVs. The map is read at
// the finest level kept, bilinear (deterministic, as the alpha test: the same normal for every
// ray that reaches the point). The tangent frame is the file's (tt.tangents) when the triangle has
// tangents, else the one made from its UVs (tangent_to_world).
MCL_INLINE SurfaceFrame apply_normal_map(SurfaceFrame fr, TextureTables tt, Material m, MCL_GLOBAL const Triangle* tri,
                                         MCL_GLOBAL const TriangleShading* sh, float3 ng0, Hit h) {
  if (!has_normal_map(m) || !(as_uint(tri->e2.w) & MCL_ATTR_UV)) return fr;
  uint tex = as_uint(m.maps.z) - 1u;
  float2 uv = surface_uv(tri, sh, h.u, h.v);
  float3 t = xyz(texture_fine(tt, tex, uv.x, uv.y));
  float4 q = map_uv_deltas(tt.textures[tex], sh);
  float3 N = unoriented_shading_normal(tri, sh, ng0, h);
  float3 n;
  if (as_uint(tri->e2.w) & MCL_ATTR_TANGENTS) {
    MCL_GLOBAL const float4* c = tt.tangents + 3u * h.tri;
    n = file_tangent_to_world(N, c[0], c[1], c[2], h.u, h.v, t);
  } else {
    n = tangent_to_world(N, xyz(tri->e1), xyz(tri->e2), q.x, q.y, q.z, q.w, t);
  }
  return normal_mapped_frame(fr, N, n, t);
}
