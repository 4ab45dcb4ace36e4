// texture.h: texture lookups, pure functions of the texture tables (types.h TextureDesc,
// TextureLevel; RGBA half texels, rows bottom to top) and of their arguments; compiled by the
// kernels, the host backend and the host tests.
// - texture_bilinear: one level, bilinear, repeat wrap (u, v in any range; v = 0 at the bottom).
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
} TextureTables;

MCL_INLINE uint texture_wrap(int i, uint n) {
  int m = i % (int)n;
  return (uint)(m < 0 ? m + (int)n : m);
}

MCL_INLINE float4 texel_at(TextureTables tt, TextureLevel l, uint x, uint y) {
  return mcl_load_half4(tt.texels, l.offset + y * l.width + x);
}

// Bilinear lookup of level `level` (an index into the level table) at (u, v), repeat wrap.
MCL_INLINE float4 texture_bilinear(TextureTables tt, uint level, float u, float v) {
  TextureLevel l = tt.levels[level];
  u -= floor(u);
  v -= floor(v);
  float x = u * (float)l.width - 0.5f, y = v * (float)l.height - 0.5f;
  float x0f = floor(x), y0f = floor(y);
  float fx = x - x0f, fy = y - y0f;
  int x0 = (int)x0f, y0 = (int)y0f;
  uint xa = texture_wrap(x0, l.width), xb = texture_wrap(x0 + 1, l.width);
  uint ya = texture_wrap(y0, l.height), yb = texture_wrap(y0 + 1, l.height);
  float4 a = texel_at(tt, l, xa, ya) * (1.0f - fx) + texel_at(tt, l, xb, ya) * fx;
  float4 b = texel_at(tt, l, xa, yb) * (1.0f - fx) + texel_at(tt, l, xb, yb) * fx;
  return a * (1.0f - fy) + b * fy;
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

// Trilinear lookup of texture `tex` at (u, v) with a footprint of `footprint` UV units.
MCL_INLINE float4 texture_sample(TextureTables tt, uint tex, float u, float v, float footprint) {
  TextureDesc d = tt.textures[tex];
  float lod = texture_lod(d, footprint);
  float l0 = floor(lod);
  float f = lod - l0;
  uint level = d.firstLevel + (uint)l0;
  float4 c = texture_bilinear(tt, level, u, v);
  if (f > 0.0f) c = c * (1.0f - f) + texture_bilinear(tt, level + 1u, u, v) * f;
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
  float4 c = texture_bilinear(tt, tt.textures[tex].firstLevel, u, v);
  uint ch = as_uint(m.alpha.z);
  return ch == 3u ? c.w : ch == 2u ? c.z : ch == 1u ? c.y : c.x;
}
