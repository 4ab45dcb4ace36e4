// surface_texture.h: textures at a triangle hit: its UVs (the per-triangle attribute buffer,
// TriangleShading, when the triangle has MCL_ATTR_UV; (0, 0) otherwise), the albedo Kd x texture
// with a ray-cone footprint, and the alpha test that every traversal applies (a hit on a cut-out
// whose alpha is below the material's cutoff does not exist; one on a stochastically transparent
// material exists with probability alpha, by a hash of the ray and the triangle). Pure; compiled by
// the kernels, the host backend and the host tests.
#pragma once
#include "geometry.h"
#include "material_kinds.h"
#include "lights.h"
#include "rng.h"
#include "texture.h"

// A triangle's texture coordinates at barycentrics (bu, bv) of corners 1 and 2 from its corners'
// (uk, vk), and the area of its UV image; written once for floats and lanes (stage_lanes.h).
#define MCL_DEFINE_SURFACE_UV(P, F)                                                                 \
  MCL_INLINE void P##uv_blend(F u0, F u1, F u2, F v0, F v1, F v2, F bu, F bv, F* u, F* v) {          \
    F w = 1.0f - bu - bv;                                                                           \
    *u = u0 * w + u1 * bu + u2 * bv;                                                                \
    *v = v0 * w + v1 * bu + v2 * bv;                                                                \
  }                                                                                                 \
  MCL_INLINE F P##uv_triangle_area(F u0, F u1, F u2, F v0, F v1, F v2) {                            \
    return 0.5f * fabs((u1 - u0) * (v2 - v0) - (u2 - u0) * (v1 - v0));                              \
  }
MCL_DEFINE_SURFACE_UV(, float)

// Texture coordinates of triangle tri (attributes sh) at barycentrics (u, v) of v1 and v2.
MCL_INLINE float2 surface_uv(MCL_GLOBAL const Triangle* tri, MCL_GLOBAL const TriangleShading* sh, float u, float v) {
  if (!(as_uint(tri->e2.w) & MCL_ATTR_UV)) return make_float2(0.0f, 0.0f);
  float x, y;
  uv_blend(sh->n0.w, sh->n1.w, sh->n2.w, sh->tv.x, sh->tv.y, sh->tv.z, u, v, &x, &y);
  return make_float2(x, y);
}

// Area of the triangle's UV image (0 without UVs).
MCL_INLINE float uv_area(MCL_GLOBAL const Triangle* tri, MCL_GLOBAL const TriangleShading* sh) {
  if (!(as_uint(tri->e2.w) & MCL_ATTR_UV)) return 0.0f;
  return uv_triangle_area(sh->n0.w, sh->n1.w, sh->n2.w, sh->tv.x, sh->tv.y, sh->tv.z);
}

// Texture tex (not MCL_NO_TEXTURE) at hit h of a camera ray along unit direction dir: trilinear,
// footprint from the camera's ray cone, camera_spread_angle(f) * h.t wide there. nA: the
// triangle's unit geometric normal (xyz) and area (w), as triangle_unit_normal and
// triangle_area_of give them.
MCL_INLINE float4 hit_texture(TextureTables tt, MCL_CONSTANT const FrameParams* f, uint tex,
                              MCL_GLOBAL const Triangle* tri, float4 nA, MCL_GLOBAL const TriangleShading* sh,
                              Hit h, float3 dir) {
  float coneWidth = camera_spread_angle(f) * h.t;
  float2 uv = surface_uv(tri, sh, h.u, h.v);
  float fp = texture_footprint(coneWidth, uv_area(tri, sh), nA.w, dot(xyz(nA), dir));
  return texture_sample(tt, tex, uv.x, uv.y, fp);
}


// Material m with its metallic-roughness texture applied at hit h (glTF: B metallic, G roughness,
// multiplying the factors in params0.x, .y; read by the metal_rough kind only); m unchanged without one.
MCL_INLINE Material hit_metal_rough(TextureTables tt, MCL_CONSTANT const FrameParams* f, Material m,
                                    MCL_GLOBAL const Triangle* tri, float4 nA, MCL_GLOBAL const TriangleShading* sh,
                                    Hit h, float3 dir) {
  uint tex = as_uint(m.maps.y);
  if (tex == MCL_NO_TEXTURE) return m;
  float4 t = hit_texture(tt, f, tex, tri, nA, sh, h, dir);
  m.params0.x *= fmin(fmax(t.z, 0.0f), 1.0f);
  m.params0.y *= fmin(fmax(t.y, 0.0f), 1.0f);
  return m;
}

// Material m with its transmission texture applied at hit h (glTF transmissionTexture: R times the
// factor in params1.x, read by transmission_mix.h's pick; params1.w holds one more than the texture,
// 0 none): m unchanged unless it is a metal_rough material with a factor > 0 and such a texture.
MCL_INLINE Material hit_transmission_texture(TextureTables tt, MCL_CONSTANT const FrameParams* f, Material m,
                                             MCL_GLOBAL const Triangle* tri, float4 nA,
                                             MCL_GLOBAL const TriangleShading* sh, Hit h, float3 dir) {
  uint slot = as_uint(m.params1.w);
  if (as_uint(m.alpha.w) != (uint)MCL_MATERIAL_metal_rough || !(m.params1.x > 0.0f) || slot == 0u) return m;
  float4 t = hit_texture(tt, f, slot - 1u, tri, nA, sh, h, dir);
  m.params1.x *= fmin(fmax(t.x, 0.0f), 1.0f);
  return m;
}

// Emission, coverage and emitter weight of an emitting triangle, written once for floats and lanes
// (P, F, F3, F4, U, M, V, ANY, LUM: the prefix, float, float3, float4, uint, int mask, f3, any and
// luminance here; the lanes' in stages/lane_lights.h). FINE(tt, tex, on, u, v) is
// texture_fine (the lanes read, where on is clear, some lane's texture, masked). The corners' UVs
// (u0..u2, t0..t2) count where hasUV is set; elsewhere the point's UV is (0, 0).
// - emission_of: Ke, times the emission texture's colour at barycentrics (bu, bv) where the
//   material has one (finest level kept, bilinear: one function of the point, the same for a light
//   sample and for a ray that hits the emitter, so the two strategies of MIS estimate the same
//   integral); no texture read where Ke is 0.
// - emitter_luminance_of: the luminance per unit area by which the emitter table weights the
//   triangle: that of Ke, or with an emission texture its mean over the triangle (the host's
//   emitters.cpp keeps it in the attributes' tv.w, tw here; a triangle without UVs emits one colour,
//   read at uv (0, 0)).
// - coverage_of: the expected coverage of a stochastically transparent material (alpha factor
//   -factor, Material alpha.y) at (u, v): the factor x its alpha texture's channel ch there
//   (alpha_hit_exists' probability). A light sample on such an emitter is weighted by it
//   (light_area.h), so light sampling and a ray that hits the emitter (which exists with this
//   probability) estimate the same emission.
#define MCL_DEFINE_EMISSION(P, F, F3, F4, U, M, V, ANY, LUM, FINE)                                                \
  MCL_INLINE M P##emits(F3 ke) { return (ke.x > 0.0f) | (ke.y > 0.0f) | (ke.z > 0.0f); }                         \
  MCL_INLINE F3 P##emission_of(TextureTables tt, F3 ke, U tex, M hasUV, F u0, F u1, F u2, F t0, F t1, F t2, F bu, \
                               F bv) {                                                                           \
    M textured = (tex != MCL_NO_TEXTURE) & P##emits(ke);                                                         \
    if (!ANY(textured)) return ke;                                                                               \
    F u, v;                                                                                                      \
    P##uv_blend(u0, u1, u2, t0, t1, t2, bu, bv, &u, &v);                                                         \
    F4 c = FINE(tt, tex, textured, vsel(hasUV, u, (F)(0.0f)), vsel(hasUV, v, (F)(0.0f)));                        \
    return V##_select(textured, V##_mul(ke, V##_make(c.x, c.y, c.z)), ke);                                       \
  }                                                                                                              \
  MCL_INLINE F P##emitter_luminance_of(TextureTables tt, F3 ke, U tex, M hasUV, F tw) {                          \
    M textured = (tex != MCL_NO_TEXTURE) & P##emits(ke);                                                         \
    F l = LUM(ke);                                                                                               \
    if (!ANY(textured)) return l;                                                                                \
    M looked = textured & (hasUV == (M)(0));                                                                     \
    F3 e = ke;                                                                                                   \
    if (ANY(looked)) {                                                                                           \
      F4 c = FINE(tt, tex, looked, (F)(0.0f), (F)(0.0f));                                                        \
      e = V##_mul(ke, V##_make(c.x, c.y, c.z));                                                                  \
    }                                                                                                            \
    return vsel(textured, vsel(hasUV, tw, LUM(e)), l);                                                           \
  }                                                                                                              \
  MCL_INLINE F P##coverage_of(TextureTables tt, F factor, U alphaTex, U ch, F u, F v, M on) {                    \
    M textured = on & (alphaTex != MCL_NO_TEXTURE);                                                              \
    F a = (F)(1.0f);                                                                                             \
    if (ANY(textured)) {                                                                                         \
      F4 c = FINE(tt, alphaTex, textured, u, v);                                                                 \
      a = vsel(textured, vsel(ch == 3u, c.w, vsel(ch == 2u, c.z, vsel(ch == 1u, c.y, c.x))), a);                 \
    }                                                                                                            \
    return -factor * a;                                                                                          \
  }
MCL_INLINE float4 mcl_texture_fine_at(TextureTables tt, uint tex, int on, float u, float v) {
  (void)on;
  return texture_fine(tt, tex, u, v);
}
MCL_DEFINE_EMISSION(, float, float3, float4, uint, int, f3, MCL_ANY1, luminance, mcl_texture_fine_at)

// The corners' UVs of the triangles tri where on is set and their attributes attrs have
// MCL_ATTR_UV (zeros elsewhere, where nothing is read), and tw the textured emitters' mean
// luminance (tv.w); returns the mask of those. Written once (P, F, U, M, ANY, G: the prefix, float,
// uint, int mask, any and mcl_gather4's prefix here; the lanes' in stages/lane_lights.h).
#define MCL_DEFINE_TRIANGLE_UVS(P, F, U, M, ANY, G)                                                         \
  MCL_INLINE M P##triangle_uvs_of(MCL_GLOBAL const TriangleShading* shading, U tri, U attrs, M on, F* u0,   \
                                  F* u1, F* u2, F* t0, F* t1, F* t2, F* tw) {                               \
    M has = on & ((attrs & MCL_ATTR_UV) != 0u);                                                             \
    *u0 = *u1 = *u2 = *t0 = *t1 = *t2 = *tw = (F)(0.0f);                                                    \
    if (ANY(has)) { /* TriangleShading: corner normals, u in w; v of the corners in tv */                   \
      MCL_GLOBAL const float* sh = (MCL_GLOBAL const float*)shading;                                        \
      const uint stride = (uint)(sizeof(TriangleShading) / sizeof(float));                                  \
      U ts = vsel(has, tri, (U)(0u));                                                                       \
      F x, y, z;                                                                                            \
      G##gather4(sh, ts, stride, &x, &y, &z, u0);                                                           \
      G##gather4(sh + 4, ts, stride, &x, &y, &z, u1);                                                       \
      G##gather4(sh + 8, ts, stride, &x, &y, &z, u2);                                                       \
      G##gather4(sh + 12, ts, stride, t0, t1, t2, tw);                                                      \
      *u0 = vsel(has, *u0, (F)(0.0f)), *u1 = vsel(has, *u1, (F)(0.0f)), *u2 = vsel(has, *u2, (F)(0.0f));   \
      *t0 = vsel(has, *t0, (F)(0.0f)), *t1 = vsel(has, *t1, (F)(0.0f)), *t2 = vsel(has, *t2, (F)(0.0f));   \
      *tw = vsel(has, *tw, (F)(0.0f));                                                                      \
    }                                                                                                       \
    return has;                                                                                             \
  }
MCL_DEFINE_TRIANGLE_UVS(, float, uint, int, MCL_ANY1, mcl_)

// Emission of material m on triangle tri (attributes sh) at barycentrics (u, v) (emission_of).
MCL_INLINE float3 material_emission(TextureTables tt, MCL_GLOBAL const Material* m, MCL_GLOBAL const Triangle* tri,
                                    MCL_GLOBAL const TriangleShading* sh, float u, float v) {
  float u0, u1, u2, t0, t1, t2, tw;
  int has = triangle_uvs_of(sh, 0u, as_uint(tri->e2.w), 1, &u0, &u1, &u2, &t0, &t1, &t2, &tw);
  return emission_of(tt, xyz(m->emission), as_uint(m->maps.x), has, u0, u1, u2, t0, t1, t2, u, v);
}

// Luminance per unit area by which the emitter table weights triangle tri of material m
// (emitter_luminance_of).
MCL_INLINE float emitter_luminance(TextureTables tt, MCL_GLOBAL const Material* m, MCL_GLOBAL const Triangle* tri,
                                   MCL_GLOBAL const TriangleShading* sh) {
  int has = (as_uint(tri->e2.w) & MCL_ATTR_UV) != 0u;
  return emitter_luminance_of(tt, xyz(m->emission), as_uint(m->maps.x), has, has ? sh->tv.w : 0.0f);
}

MCL_INLINE TextureTables make_texture_tables(MCL_GLOBAL const TextureDesc* textures,
                                             MCL_GLOBAL const TextureLevel* levels, MCL_GLOBAL const ushort* texels) {
  TextureTables tt;
  tt.textures = textures;
  tt.levels = levels;
  tt.texels = texels;
  tt.colors = 0;
  tt.tangents = 0;
  return tt;
}

// The texture tables with the vertex colours and corner tangents (what the shade stages read).
MCL_INLINE TextureTables make_surface_tables(MCL_GLOBAL const TextureDesc* textures, MCL_GLOBAL const TextureLevel* levels,
                                             MCL_GLOBAL const ushort* texels, MCL_GLOBAL const float4* colors,
                                             MCL_GLOBAL const float4* tangents) {
  TextureTables tt = make_texture_tables(textures, levels, texels);
  tt.colors = colors;
  tt.tangents = tangents;
  return tt;
}

// What the alpha test reads. Traversals take a pointer to one; a null pointer: every hit exists.
typedef struct AlphaScene {
  MCL_GLOBAL const Material* materials;
  MCL_GLOBAL const TriangleShading* shading;
  TextureTables tex;
} AlphaScene;

MCL_INLINE AlphaScene make_alpha_scene(MCL_GLOBAL const Material* materials, MCL_GLOBAL const TriangleShading* shading,
                                       TextureTables tt) {
  AlphaScene s;
  s.materials = materials;
  s.shading = shading;
  s.tex = tt;
  return s;
}

// A uniform number in [0, 1) that is a function of a ray (its origin's and direction's bits) and a
// triangle (its canonical slot): the stochastic transparency's coin for that ray and triangle (as
// pbrt-v4's HashFloat(o, d) of its alpha test). Every traversal (binary, wide, two rays
// interleaved, packets lane by lane) sees the same ray bits and slot, so every device, lane width
// and wave shape makes the same choice; the slot tells apart the surfaces one ray crosses (pbrt
// spawns a new ray past each), and an instance's ray is in its object space, so two placements of
// one triangle choose apart too.
MCL_INLINE float alpha_coin(float3 o, float3 d, uint canon) {
  return u32_to_unit(mcl_mix_float3(mcl_mix_float3(mcl_mix32(canon ^ 0x5bd1e995u), o), d));
}

// 0 when triangle i of tris is alpha-tested (MCL_ATTR_ALPHA) and its hit at (u, v) by the ray
// o + t d does not exist: for a cut-out (Material alpha.y >= 0, its sign bit clear) when the
// material's alpha there is below the cutoff; for stochastic transparency (glTF BLEND: the sign
// bit set, -alpha.y the alpha factor) with probability 1 - factor x alpha, decided by
// alpha_coin. Deterministic: the finest level kept, bilinear; the coin a hash. The one alpha test:
// the packet traversals run it lane by lane.
MCL_INLINE int alpha_hit_exists(const AlphaScene* a, MCL_GLOBAL const Triangle* tris, uint i, float u, float v,
                                float3 o, float3 d) {
  if (!a || !(as_uint(tris[i].e2.w) & MCL_ATTR_ALPHA)) return 1;
  Material m = a->materials[as_uint(tris[i].v0.w)];
  float2 uv = surface_uv(&tris[i], &a->shading[i], u, v);
  float alpha = alpha_value(a->tex, m, uv.x, uv.y);
  if (!(as_uint(m.alpha.y) & 0x80000000u)) return alpha >= m.alpha.y;
  return alpha_coin(o, d, as_uint(tris[i].e1.w)) < -m.alpha.y * alpha;
}
