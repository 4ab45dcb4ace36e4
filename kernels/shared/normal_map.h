// normal_map.h: the tangent-space normal map of a hit: reads the material's normal texture
// (Material::params1.w, MCL_NO_TEXTURE: none; texels hold the decoded tangent-space vector
// ((2r - 1) s, (2g - 1) s, 2b - 1), s the map's scale, baked in by the host), the triangle's UVs
// and edges, and writes the perturbed shading normal of a SurfaceFrame. Pure; compiled by the
// kernels, the host backend and the host tests.
#pragma once
#include "shading.h"
#include "surface_texture.h"

// Material m's normal texture index (MCL_NO_TEXTURE: none).
MCL_INLINE uint normal_texture(Material m) { return as_uint(m.params1.w); }

// The frame fr with its shading normal perturbed by the tangent-space vector t (texel of the
// normal map at the hit). The tangent frame: T, B = dP/du, dP/dv of the triangle (its edges
// e1, e2 over its UV deltas; constant per triangle: this approximates MikkTSpace, which
// averages them per vertex, and equals it on planar UV-linear patches), T orthogonalised
// against the unoriented shading normal n0 (Gram-Schmidt), B = sign x cross(n0, T) with the
// handedness sign of the UV map. Then n = normalize(t.x T + t.y B + t.z n0) on ng's side (the
// rule of interpolated normals). Unchanged (bit for bit) when t = (0, 0, z): a flat map, when the
// UVs are degenerate or the result is no usable direction.
MCL_INLINE SurfaceFrame normal_mapped_frame(SurfaceFrame fr, float3 n0, float3 e1, float3 e2, float2 uv0,
                                            float2 uv1, float2 uv2, float3 t) {
  float du1 = uv1.x - uv0.x, dv1 = uv1.y - uv0.y, du2 = uv2.x - uv0.x, dv2 = uv2.y - uv0.y;
  float det = du1 * dv2 - du2 * dv1;
  float3 T = e1 * dv2 - e2 * dv1;  // dP/du x det
  float3 B = e2 * du1 - e1 * du2;  // dP/dv x det
  float hand = dot(cross(n0, T), B) * det < 0.0f ? -1.0f : 1.0f;
  float3 To = T - n0 * dot(n0, T);
  float tl2 = dot(To, To);
  To = To * (1.0f / sqrt(fmax(tl2, 1e-30f)));
  float3 Bo = cross(n0, To) * hand;
  float3 n = To * t.x + Bo * t.y + n0 * t.z;
  float nl2 = dot(n, n);
  n = n * (1.0f / sqrt(fmax(nl2, 1e-30f)));
  int use = (t.x != 0.0f || t.y != 0.0f) && det != 0.0f && tl2 > 1e-30f && nl2 > 1e-20f && nl2 < INFINITY &&
            fabs(det) < INFINITY;
  SurfaceFrame s = fr;
  float3 no = orient_to(n, fr.ng);
  s.ns = use ? no : fr.ns;
  s.smooth = use ? 1 : fr.smooth;
  return s;
}

// The frame fr of hit h on triangle tri (attributes sh, unit geometric normal ng0 unoriented)
// under material m's normal map; fr unchanged without a map or without UVs. The map is read at
// the finest level kept, bilinear (deterministic, as the alpha test).
MCL_INLINE SurfaceFrame apply_normal_map(SurfaceFrame fr, TextureTables tt, Material m, MCL_GLOBAL const Triangle* tri,
                                         MCL_GLOBAL const TriangleShading* sh, float3 ng0, Hit h) {
  uint tex = normal_texture(m);
  if (tex == MCL_NO_TEXTURE || !(as_uint(tri->e2.w) & MCL_ATTR_UV)) return fr;
  float2 uv = surface_uv(tri, sh, h.u, h.v);
  float3 t = xyz(texture_bilinear(tt, tt.textures[tex].firstLevel, uv.x, uv.y));
  float3 n0 = ng0;
  if (as_uint(tri->e2.w) & MCL_ATTR_NORMALS) {
    float3 n = interpolate_normal(xyz(sh->n0), xyz(sh->n1), xyz(sh->n2), h.u, h.v);
    n0 = dot(n, n) > 0.0f ? n : ng0;
  }
  return normal_mapped_frame(fr, n0, xyz(tri->e1), xyz(tri->e2), make_float2(sh->n0.w, sh->tv.x),
                             make_float2(sh->n1.w, sh->tv.y), make_float2(sh->n2.w, sh->tv.z), t);
}
