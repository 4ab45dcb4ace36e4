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

// Texel i (in units of its format's size) of a level of format `format` (MCL_TEXELS_*): half
// texels as stored; 8-bit codes (r, g in the first ushort, b, a in the second, low byte first)
// through the tables at the buffer's start.
MCL_INLINE float4 texel_fetch(TextureTables tt, uint format, uint i) {
  if (format == MCL_TEXELS_HALF) return mcl_load_half4(tt.texels, i);
  MCL_GLOBAL const ushort* q = tt.texels + 2u * (ulong)i;
  uint rg = q[0], ba = q[1];
  uint rgb = format == MCL_TEXELS_SRGB8 ? 0u : 256u;
  return make_float4(mcl_load_half(tt.texels, rgb + (rg & 0xffu)), mcl_load_half(tt.texels, rgb + (rg >> 8)),
                     mcl_load_half(tt.texels, rgb + (ba & 0xffu)), mcl_load_half(tt.texels, 256u + (ba >> 8)));
}

MCL_INLINE float4 texel_at(TextureTables tt, TextureLevel l, uint x, uint y) {
  return texel_fetch(tt, l.format, l.offset + y * l.width + x);
}

// The lookups below are written once over a float type F (with its uint U and int I types, the
// four-channel F4 made by MAKE4, the select SEL, ANY of a mask, the conversions and bit casts) and
// the readers of a texture's description (DESC_T, DESC), of a level (LEVEL_T, LEVEL) and of a
// texel (TEXEL): below for float, and in kernels/stages/stage_lanes.h for the lanes of a packet,
// whose gathers issue every lane's texel reads at once. Each lane performs the float body's
// operations in the same order, so a lane gives the float function's bits.
#define MCL_DEFINE_TEXTURE_LOOKUP(P, F, U, I, F4, MAKE4, SEL, ANY, U_OF_I, I_OF_U, I_OF_F, U_OF_F, F_OF_U, AS_U,  \
                                  AS_F, DESC_T, DESC, LEVEL_T, LEVEL, TEXEL)                                     \
  /* Texel index i of a row of n texels, repeated (i mod n). */                                                 \
  MCL_INLINE U P##texture_wrap(I i, U n) {                                                                      \
    I m = i % I_OF_U(n);                                                                                        \
    return U_OF_I(SEL(m < 0, m + I_OF_U(n), m));                                                              \
  }                                                                                                             \
  /* Texel index i of a row of n texels under wrap mode w: repeat (i mod n), clamp to [0, n - 1], or mirrored  \
     repeat (period 2n, the second half reversed). Branch-free: every mode computed, one kept. */               \
  MCL_INLINE U P##texture_wrap_mode(I i, U n, U w) {                                                            \
    U r = P##texture_wrap(i, n);                                                                                \
    U c = U_OF_I(SEL(i < 0, (I)(0), SEL(i > I_OF_U(n) - 1, I_OF_U(n) - 1, i)));                                \
    U m2 = P##texture_wrap(i, 2u * n);                                                                          \
    U m = SEL(m2 >= n, 2u * n - 1u - m2, m2);                                                                   \
    return SEL(w == MCL_WRAP_CLAMP, c, SEL(w == MCL_WRAP_MIRROR, m, r));                                        \
  }                                                                                                             \
  /* A coordinate brought into the range its wrap mode repeats: [0, 1) repeat, [0, 2) mirrored repeat, [0, 1]  \
     clamp (keeps the texel arithmetic small; the index wrap does the rest). */                                 \
  MCL_INLINE F P##texture_reduce(F u, U w) {                                                                    \
    F r = u - floor(u);                                                                                         \
    F m = u - 2.0f * floor(0.5f * u);                                                                           \
    F c = fmin(fmax(u, 0.0f), 1.0f);                                                                            \
    return SEL(w == MCL_WRAP_CLAMP, c, SEL(w == MCL_WRAP_MIRROR, m, r));                                        \
  }                                                                                                             \
  /* a (1 - t) + b t, channel by channel. */                                                                    \
  MCL_INLINE F4 P##texel_lerp(F4 a, F4 b, F t) {                                                                \
    return MAKE4(a.x * (1.0f - t) + b.x * t, a.y * (1.0f - t) + b.y * t, a.z * (1.0f - t) + b.z * t,           \
                 a.w * (1.0f - t) + b.w * t);                                                                   \
  }                                                                                                             \
  /* Bilinear lookup of level `level` (an index into the level table) at (u, v), wrap modes ws (u) and wt    \
     (v). */                                                                                                    \
  MCL_INLINE F4 P##texture_bilinear_wrap(TextureTables tt, U level, F u, F v, U ws, U wt) {                     \
    LEVEL_T l = LEVEL(tt, level);                                                                               \
    u = P##texture_reduce(u, ws);                                                                               \
    v = P##texture_reduce(v, wt);                                                                               \
    F x = u * F_OF_U(l.width) - 0.5f, y = v * F_OF_U(l.height) - 0.5f;                                          \
    F x0f = floor(x), y0f = floor(y);                                                                           \
    F fx = x - x0f, fy = y - y0f;                                                                               \
    I x0 = I_OF_F(x0f), y0 = I_OF_F(y0f);                                                                       \
    U xa = P##texture_wrap_mode(x0, l.width, ws), xb = P##texture_wrap_mode(x0 + 1, l.width, ws);               \
    U ya = P##texture_wrap_mode(y0, l.height, wt), yb = P##texture_wrap_mode(y0 + 1, l.height, wt);             \
    F4 a = P##texel_lerp(TEXEL(tt, l, xa, ya), TEXEL(tt, l, xb, ya), fx);                                       \
    F4 b = P##texel_lerp(TEXEL(tt, l, xa, yb), TEXEL(tt, l, xb, yb), fx);                                       \
    return P##texel_lerp(a, b, fy);                                                                             \
  }                                                                                                             \
  /* Texture d's coordinates (*x, *y) for the surface's (u, v): its affine UV transform (identity rows: (u, v) \
     exactly). */                                                                                               \
  MCL_INLINE void P##texture_uv_of(DESC_T d, F u, F v, F* x, F* y) {                                            \
    *x = d.uvRow0.x * u + d.uvRow0.y * v + d.uvRow0.z;                                                          \
    *y = d.uvRow1.x * u + d.uvRow1.y * v + d.uvRow1.z;                                                          \
  }                                                                                                             \
  /* How much texture d's transform scales lengths in UV (the square root of its area scale; 1 for the       \
     identity): a footprint in the surface's UVs times this is one in the texture's. */                         \
  MCL_INLINE F P##texture_uv_scale(DESC_T d) {                                                                  \
    return sqrt(fabs(d.uvRow0.x * d.uvRow1.y - d.uvRow0.y * d.uvRow1.x));                                       \
  }                                                                                                             \
  /* log2(x) for finite x > 0 from its exponent bits and + x / only (division correctly rounded, see          \
     cl_session.cpp): the built-in log2 differs in the last bit between PoCL and glibc, which moved trilinear  \
     weights and broke bit-identical images. Absolute error < 2e-6 (atanh series to s^11, |s| <= 1/3), plenty \
     for a level of detail. Zero or denormal (flushed on some devices): -150, below any level. */              \
  MCL_INLINE F P##texture_log2(F x) {                                                                           \
    U bits = AS_U(x);                                                                                           \
    U biased = (bits >> 23) & 0xffu;                                                                            \
    F m = AS_F((bits & 0x807fffffu) | 0x3f000000u); /* x = m 2^e, m in [1/2, 1) */                              \
    F e = F_OF_U(biased) - 126.0f;                  /* exact: small integers */                                 \
    F s = (m - 1.0f) / (m + 1.0f), s2 = s * s;                                                                  \
    F p = 0.33333334f + s2 * (0.2f + s2 * (0.14285715f + s2 * (0.11111111f + s2 * 0.09090909f)));              \
    return SEL(biased == 0u, (F)(-150.0f), e + (2.0f * s * (1.0f + s2 * p)) * 1.44269504f);                    \
  }                                                                                                             \
  /* Level of detail in the kept levels of texture d for a footprint (UV units), in [0, levelCount - 1]. */    \
  MCL_INLINE F P##texture_lod(DESC_T d, F footprint) {                                                          \
    F lod = SEL((footprint > 0.0f) & (footprint < INFINITY),                                                    \
                P##texture_log2(footprint) + d.lodBias - F_OF_U(d.dropped),                                     \
                SEL(footprint > 0.0f, (F)(INFINITY), (F)(0.0f)));                                               \
    F top = F_OF_U(d.levelCount - 1u);                                                                          \
    return SEL(lod > 0.0f, SEL(lod < top, lod, top), (F)(0.0f)); /* NaN -> 0 */                                \
  }                                                                                                             \
  /* Trilinear lookup of texture `tex` at the surface's (u, v) (through the texture's transform and wrap      \
     modes) with a footprint of `footprint` surface UV units. */                                                \
  MCL_INLINE F4 P##texture_sample(TextureTables tt, U tex, F u, F v, F footprint) {                             \
    DESC_T d = DESC(tt, tex);                                                                                   \
    F tx, ty;                                                                                                   \
    P##texture_uv_of(d, u, v, &tx, &ty);                                                                        \
    U ws = AS_U(d.uvRow0.w), wt = AS_U(d.uvRow1.w);                                                             \
    F lod = P##texture_lod(d, footprint * P##texture_uv_scale(d));                                              \
    F l0 = floor(lod);                                                                                          \
    F f = lod - l0;                                                                                             \
    U level = d.firstLevel + U_OF_F(l0);                                                                        \
    F4 c = P##texture_bilinear_wrap(tt, level, tx, ty, ws, wt);                                                 \
    if (ANY(f > 0.0f)) {                                                                                        \
      F4 fine = P##texel_lerp(c, P##texture_bilinear_wrap(tt, SEL(f > 0.0f, level + 1u, level), tx, ty, ws, wt), f); \
      c = MAKE4(SEL(f > 0.0f, fine.x, c.x), SEL(f > 0.0f, fine.y, c.y), SEL(f > 0.0f, fine.z, c.z),              \
                SEL(f > 0.0f, fine.w, c.w));                                                                    \
    }                                                                                                           \
    return c;                                                                                                   \
  }                                                                                                             \
  /* Footprint in UV units of a cone of width coneWidth at a hit on a triangle with UV area uvArea and world  \
     area worldArea, seen at cosine cosTheta between the ray and the normal. */                                 \
  MCL_INLINE F P##texture_footprint(F coneWidth, F uvArea, F worldArea, F cosTheta) {                           \
    F c = fabs(cosTheta);                                                                                       \
    F r = coneWidth * sqrt(uvArea / worldArea) / SEL(c > 1e-4f, c, (F)(1e-4f));                                 \
    return SEL((worldArea > 0.0f) & (uvArea > 0.0f), r, (F)(0.0f));                                            \
  }

#define MCL_TEXTURE_DESC(tt, i) ((tt).textures[i])
#define MCL_TEXTURE_LEVEL(tt, i) ((tt).levels[i])
MCL_DEFINE_TEXTURE_LOOKUP(, float, uint, int, float4, make_float4, MCL_SEL1, MCL_ANY1, (uint), (int), (int), (uint),
                          (float), as_uint, as_float, TextureDesc, MCL_TEXTURE_DESC, TextureLevel, MCL_TEXTURE_LEVEL,
                          texel_at)

// Bilinear lookup of level `level` at (u, v), repeat wrap.
MCL_INLINE float4 texture_bilinear(TextureTables tt, uint level, float u, float v) {
  return texture_bilinear_wrap(tt, level, u, v, MCL_WRAP_REPEAT, MCL_WRAP_REPEAT);
}

// Texture d's coordinates for the surface's (u, v).
MCL_INLINE float2 texture_uv(TextureDesc d, float u, float v) {
  float x, y;
  texture_uv_of(d, u, v, &x, &y);
  return make_float2(x, y);
}

// Texture tex (an index into the texture table) at the surface's (u, v): the finest level kept,
// bilinear, through the texture's transform and wrap modes.
MCL_INLINE float4 texture_fine(TextureTables tt, uint tex, float u, float v) {
  TextureDesc d = tt.textures[tex];
  float2 t = texture_uv(d, u, v);
  return texture_bilinear_wrap(tt, d.firstLevel, t.x, t.y, as_uint(d.uvRow0.w), as_uint(d.uvRow1.w));
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
