// texture.h: texture lookups, pure functions of the texture tables (types.h TextureDesc,
// TextureLevel; RGBA half texels, rows bottom to top) and of their arguments; compiled by the
// kernels, the host backend and the host tests.
// - texture_bilinear: one level, bilinear, repeat wrap (u, v in any range; v = 0 at the bottom);
//   texture_bilinear_wrap: the same with a wrap mode per axis (MCL_WRAP_*).
// - texture_uv: a texture's own UV transform (TextureDesc uvRow0/1); texture_fine: the finest level
//   kept of a texture, through its transform and wrap modes (the deterministic lookups).
// - texture_sample: trilinear between the two levels around lod = log2(footprint * size), where
//   footprint is the width of the lookup's footprint in UV units (0: the finest level kept).
// - ray cones (camera rays): the cone's spread is the pixel's angular size; its width at a hit is
//   spread * distance; texture_footprint turns it into UV units with the triangle's UV/position
//   area ratio, divided by |cos| between the ray and the surface (a grazing hit covers more).
// - alpha_value: the material's alpha at a hit (finest level kept, bilinear: deterministic).
#pragma once
#include "types.h"

typedef struct {
  MCL_GLOBAL const TextureDesc* textures;
  MCL_GLOBAL const TextureLevel* levels;
  MCL_GLOBAL const ushort* texels;
  MCL_GLOBAL const float4* colors;  // vertex colours (MCL_ATTR_COLOR; read by hit_albedo only; may be null elsewhere)
  MCL_GLOBAL const float4* tangents;  // corner tangents (MCL_ATTR_TANGENTS; read by apply_normal_map only; may be null elsewhere)
} TextureTables;

MCL_INLINE uint texture_wrap(int i, uint n) {
  int m = i % (int)n;
  return (uint)(m < 0 ? m + (int)n : m);
}

MCL_INLINE float4 texel_at(TextureTables tt, TextureLevel l, uint x, uint y) {
  return mcl_load_half4(tt.texels, l.offset + y * l.width + x);
}

// Texel index i of a row of n texels under wrap mode w: repeat (i mod n), clamp to [0, n - 1], or
// mirrored repeat (period 2n, the second half reversed). Branch-free: every mode computed, one kept.
MCL_INLINE uint texture_wrap_mode(int i, uint n, uint w) {
  uint r = texture_wrap(i, n);
  uint c = (uint)(i < 0 ? 0 : i > (int)n - 1 ? (int)n - 1 : i);
  uint m2 = texture_wrap(i, 2u * n);
  uint m = m2 >= n ? 2u * n - 1u - m2 : m2;
  return w == MCL_WRAP_CLAMP ? c : w == MCL_WRAP_MIRROR ? m : r;
}

// A coordinate brought into the range its wrap mode repeats: [0, 1) repeat, [0, 2) mirrored
// repeat, [0, 1] clamp (keeps the texel arithmetic small; the index wrap does the rest).
MCL_INLINE float texture_reduce(float u, uint w) {
  float r = u - floor(u);
  float m = u - 2.0f * floor(0.5f * u);
  float c = fmin(fmax(u, 0.0f), 1.0f);
  return w == MCL_WRAP_CLAMP ? c : w == MCL_WRAP_MIRROR ? m : r;
}

// Bilinear lookup of level `level` (an index into the level table) at (u, v), wrap modes ws (u)
// and wt (v).
MCL_INLINE float4 texture_bilinear_wrap(TextureTables tt, uint level, float u, float v, uint ws, uint wt) {
  TextureLevel l = tt.levels[level];
  u = texture_reduce(u, ws);
  v = texture_reduce(v, wt);
  float x = u * (float)l.width - 0.5f, y = v * (float)l.height - 0.5f;
  float x0f = floor(x), y0f = floor(y);
  float fx = x - x0f, fy = y - y0f;
  int x0 = (int)x0f, y0 = (int)y0f;
  uint xa = texture_wrap_mode(x0, l.width, ws), xb = texture_wrap_mode(x0 + 1, l.width, ws);
  uint ya = texture_wrap_mode(y0, l.height, wt), yb = texture_wrap_mode(y0 + 1, l.height, wt);
  float4 a = texel_at(tt, l, xa, ya) * (1.0f - fx) + texel_at(tt, l, xb, ya) * fx;
  float4 b = texel_at(tt, l, xa, yb) * (1.0f - fx) + texel_at(tt, l, xb, yb) * fx;
  return a * (1.0f - fy) + b * fy;
}

// Bilinear lookup of level `level` at (u, v), repeat wrap.
MCL_INLINE float4 texture_bilinear(TextureTables tt, uint level, float u, float v) {
  return texture_bilinear_wrap(tt, level, u, v, MCL_WRAP_REPEAT, MCL_WRAP_REPEAT);
}

// Texture d's coordinates for the surface's (u, v): its affine UV transform (identity rows: (u, v)
// exactly).
MCL_INLINE float2 texture_uv(TextureDesc d, float u, float v) {
  return make_float2(d.uvRow0.x * u + d.uvRow0.y * v + d.uvRow0.z, d.uvRow1.x * u + d.uvRow1.y * v + d.uvRow1.z);
}

// How much texture d's transform scales lengths in UV (the square root of its area scale; 1 for
// the identity): a footprint in the surface's UVs times this is one in the texture's.
MCL_INLINE float texture_uv_scale(TextureDesc d) {
  return sqrt(fabs(d.uvRow0.x * d.uvRow1.y - d.uvRow0.y * d.uvRow1.x));
}

// Texture tex (an index into the texture table) at the surface's (u, v): the finest level kept,
// bilinear, through the texture's transform and wrap modes.
MCL_INLINE float4 texture_fine(TextureTables tt, uint tex, float u, float v) {
  TextureDesc d = tt.textures[tex];
  float2 t = texture_uv(d, u, v);
  return texture_bilinear_wrap(tt, d.firstLevel, t.x, t.y, as_uint(d.uvRow0.w), as_uint(d.uvRow1.w));
}

// log2(x) for finite x > 0 from its exponent bits and + x / only (division correctly rounded, see
// cl_session.cpp): the built-in log2 differs in the last bit between PoCL and glibc, which moved
// trilinear weights and broke bit-identical images. Absolute error < 2e-6 (atanh series to s^11,
// |s| <= 1/3), plenty for a level of detail.
MCL_INLINE float texture_log2(float x) {
  uint bits = as_uint(x);
  uint biased = (bits >> 23) & 0xffu;
  if (biased == 0u) return -150.0f;  // zero or denormal (flushed on some devices): below any level
  float m = as_float((bits & 0x807fffffu) | 0x3f000000u);  // x = m 2^e, m in [0.5, 1)
  int e = (int)biased - 126;
  float s = (m - 1.0f) / (m + 1.0f), s2 = s * s;
  float p = 0.33333334f + s2 * (0.2f + s2 * (0.14285715f + s2 * (0.11111111f + s2 * 0.09090909f)));
  return (float)e + (2.0f * s * (1.0f + s2 * p)) * 1.44269504f;
}

// Level of detail in the kept levels of texture d for a footprint (UV units), in [0, levelCount - 1].
MCL_INLINE float texture_lod(TextureDesc d, float footprint) {
  float lod = footprint > 0.0f && footprint < INFINITY ? texture_log2(footprint) + d.lodBias - (float)d.dropped
              : footprint > 0.0f                       ? INFINITY
                                                       : 0.0f;
  float top = (float)(d.levelCount - 1u);
  return lod > 0.0f ? (lod < top ? lod : top) : 0.0f;  // NaN -> 0
}

// Trilinear lookup of texture `tex` at the surface's (u, v) (through the texture's transform and
// wrap modes) with a footprint of `footprint` surface UV units.
MCL_INLINE float4 texture_sample(TextureTables tt, uint tex, float u, float v, float footprint) {
  TextureDesc d = tt.textures[tex];
  float2 t = texture_uv(d, u, v);
  uint ws = as_uint(d.uvRow0.w), wt = as_uint(d.uvRow1.w);
  float lod = texture_lod(d, footprint * texture_uv_scale(d));
  float l0 = floor(lod);
  float f = lod - l0;
  uint level = d.firstLevel + (uint)l0;
  float4 c = texture_bilinear_wrap(tt, level, t.x, t.y, ws, wt);
  if (f > 0.0f) c = c * (1.0f - f) + texture_bilinear_wrap(tt, level + 1u, t.x, t.y, ws, wt) * f;
  return c;
}

// Footprint in UV units of a cone of width coneWidth at a hit on a triangle with UV area uvArea
// and world area worldArea, seen at cosine cosTheta between the ray and the normal.
MCL_INLINE float texture_footprint(float coneWidth, float uvArea, float worldArea, float cosTheta) {
  if (!(worldArea > 0.0f) || !(uvArea > 0.0f)) return 0.0f;
  float c = fabs(cosTheta);
  return coneWidth * sqrt(uvArea / worldArea) / (c > 1e-4f ? c : 1e-4f);
}

// Spread angle of the camera's ray cones: the angular size of one pixel at the image centre.
MCL_INLINE float camera_spread_angle(MCL_CONSTANT const FrameParams* f) {
  float3 centre = xyz(f->camTopLeft) + xyz(f->camDx) * (0.5f * (float)f->width) +
                  xyz(f->camDy) * (0.5f * (float)f->height);
  return length(xyz(f->camDy)) / length(centre);
}

// Alpha of material m at (u, v): its alpha texture's channel (material alpha.z) at the finest level
// kept, bilinear; 1 without an alpha texture.
MCL_INLINE float alpha_value(TextureTables tt, Material m, float u, float v) {
  uint tex = as_uint(m.alpha.x);
  if (tex == MCL_NO_TEXTURE) return 1.0f;
  float4 c = texture_fine(tt, tex, u, v);
  uint ch = as_uint(m.alpha.z);
  return ch == 3u ? c.w : ch == 2u ? c.z : ch == 1u ? c.y : c.x;
}
