// sheen.h: glTF KHR_materials_sheen's layer for the metal_rough kind (bsdf_metal_rough.h): the
// "Charlie" fibre distribution of Estevez and Kulla (2017) with their visibility term (the one the
// extension's implementation notes give first, whose lambda fit it quotes), and the lobe's
// directional albedo E for the extension's albedo scaling, from + - * / and exp_neg.h only (the
// same bits on every device and on the host). Pure; compiled by the kernels and the host tests.
#pragma once
#include "exp_neg.h"
#include "sampling.h"  // MCL_INV_PI

// The smallest sheen roughness (glTF's perceptual r; alpha = r^2): the extension's sample
// implementation clamps r to (0, 1] this way, so r = 0 is a very sharp, grazing-only sheen.
#define MCL_SHEEN_MIN_ROUGHNESS 1e-6f

// E(mu, r): the lobe's directional albedo at cos(theta_o) = mu (sheen colour 1), a fit (no table:
// OpenCL 1.2 has no program-scope constants to hold one): sum c[i][j] T_i(1 - 2s) T_j(tr), T the
// Chebyshev polynomials, s = mu / (mu + r / 2), tr = (2r - 1.15) / 0.85, r clamped to [0.15, 1];
// least squares on 35 x 45 values of E integrated in double precision (r = 0.15 .. 1, mu = 0.002 ..
// 1, 80,000 directions each). Largest error 0.027 (at mu = 0.002, the grazing end), 0.02 from
// mu = 0.05 and 0.011 from mu = 0.1 up (the extension allows an approximate E); below
// r = 0.15 it is E(mu, 0.15), above the true E except at grazing views (mu < ~0.1), where a sharp
// sheen's true E grows past 1 (the Charlie lobe is not energy conserving there). tests/
// test_bsdf_sheen.cpp checks the fit against its own quadrature of the lobe.
#define MCL_SHEEN_E_ROW(a, b, c, d, e, f) ((a) + tr * (b) + T2 * (c) + T3 * (d) + T4 * (e) + T5 * (f))

// Written once for floats and lanes (P, E, F, U, M, F3, V: the prefix, exp_neg's prefix, float,
// uint, int mask, float3, f3 here; the packet stages' v_, v_, vfloat, vuint, vmask, vfloat3, v3 in
// stages/lane_bsdf.h, with the bit casts F -> U (AS_U), U -> F (AS_F) and the conversion U -> F
// (F_OF_U)).
// - sheen_ln: ln x for x >= 0 (mantissa in [0.75, 1.5], so relative accuracy near 1; 0 or a
//   denormal: -1e30); sheen_pow: x^k for x in [0, 1], k > 0; sheen_exp: e^y for any y.
// - sheen_alpha: alpha = max(r, MCL_SHEEN_MIN_ROUGHNESS)^2.
// - sheen_d: D(h) = (2 + 1/alpha) sin(h)^(1/alpha) / (2 pi) at cos(h) = c.
// - sheen_lambda: the visibility fit's Lambda(cos) (Estevez and Kulla's l(x), exp(l(c)) below 1/2,
//   exp(2 l(1/2) - l(1 - c)) above).
// - sheen_lobe: f cos of the lobe with colour 1, D(h) / ((1 + Lambda(mu_o) + Lambda(mu_i)) 4 mu_o)
//   (V = 1 / ((1 + Lambda_o + Lambda_i) 4 mu_o mu_i) times D times mu_i); 0 unless both above.
// - sheen_albedo: the fit E(mu, r) above (>= 0).
// - sheen_scaling: the base's factor, 1 - max(colour) E(mu_o, r), in [0, 1] (the extension's
//   simplified albedo scaling, by the view direction alone).
#define MCL_DEFINE_SHEEN(P, E, F, U, M, F3, V, AS_U, AS_F, F_OF_U)                                            \
  MCL_INLINE F P##sheen_ln(F x) {                                                                             \
    U bits = AS_U(x);                                                                                         \
    U biased = (bits >> 23) & 0xffu;                                                                          \
    F m = AS_F((bits & 0x007fffffu) | 0x3f800000u); /* [1, 2) */                                              \
    F e = F_OF_U(biased) - 127.0f;                                                                            \
    M big = m > 1.5f;                                                                                         \
    m = vsel(big, m * 0.5f, m);                                                                               \
    e = vsel(big, e + 1.0f, e);                                                                               \
    F s = (m - 1.0f) / (m + 1.0f), s2 = s * s;                                                                \
    F p = 1.0f + s2 * (0.33333334f + s2 * (0.2f + s2 * (0.14285715f + s2 * (0.11111111f + s2 * 0.09090909f)))); \
    return vsel(biased == 0u, (F)(-1e30f), e * 0.693147181f + 2.0f * s * p);                                  \
  }                                                                                                           \
  MCL_INLINE F P##sheen_pow(F x, F k) { return E##exp_neg(-(k * fmin(P##sheen_ln(x), 0.0f))); }               \
  MCL_INLINE F P##sheen_exp(F y) {                                                                            \
    F n = E##exp_neg(fabs(y));                                                                                \
    return vsel(y > 0.0f, 1.0f / n, n);                                                                       \
  }                                                                                                           \
  MCL_INLINE F P##sheen_alpha(F r) {                                                                          \
    F g = fmax(r, MCL_SHEEN_MIN_ROUGHNESS);                                                                   \
    return g * g;                                                                                             \
  }                                                                                                           \
  MCL_INLINE F P##sheen_d(F c, F alpha) {                                                                     \
    F inv = 1.0f / alpha;                                                                                     \
    F sin2 = fmax(1.0f - c * c, 0.0f);                                                                        \
    return (2.0f + inv) * P##sheen_pow(sin2, 0.5f * inv) * (0.5f * MCL_INV_PI);                               \
  }                                                                                                           \
  MCL_INLINE F P##sheen_l(F x, F alpha) {                                                                     \
    F t = (1.0f - alpha) * (1.0f - alpha);                                                                    \
    F a = 21.5473f + (25.3245f - 21.5473f) * t;                                                               \
    F b = 3.82987f + (3.32435f - 3.82987f) * t;                                                               \
    F c = 0.19823f + (0.16801f - 0.19823f) * t;                                                               \
    F d = -1.97760f + (-1.27393f + 1.97760f) * t;                                                             \
    F e = -4.32054f + (-4.85967f + 4.32054f) * t;                                                             \
    return a / (1.0f + b * P##sheen_pow(x, c)) + d * x + e;                                                   \
  }                                                                                                           \
  MCL_INLINE F P##sheen_lambda(F c, F alpha) {                                                                \
    M low = c < 0.5f;                                                                                         \
    F lx = P##sheen_l(vsel(low, c, 1.0f - c), alpha);                                                         \
    return P##sheen_exp(vsel(low, lx, 2.0f * P##sheen_l((F)(0.5f), alpha) - lx));                            \
  }                                                                                                           \
  MCL_INLINE F P##sheen_lobe(F3 woL, F3 wiL, F alpha) {                                                       \
    M ok = (woL.z > 0.0f) & (wiL.z > 0.0f);                                                                   \
    F3 h = V##_normalize(V##_add(woL, wiL));                                                                  \
    F lo = P##sheen_lambda(fmin(woL.z, 1.0f), alpha), li = P##sheen_lambda(fmin(wiL.z, 1.0f), alpha);         \
    F f = P##sheen_d(h.z, alpha) / ((1.0f + lo + li) * (4.0f * woL.z));                                       \
    return vsel(ok, f, (F)(0.0f));                                                                            \
  }                                                                                                           \
  MCL_INLINE F P##sheen_albedo(F mu, F r) {                                                                   \
    F rr = fmin(fmax(r, 0.15f), 1.0f);                                                                        \
    F m = fmin(fmax(mu, 0.0f), 1.0f);                                                                         \
    F sx = m / (m + 0.5f * rr);                                                                               \
    F tx = 1.0f - 2.0f * sx, tr = (2.0f * rr - 1.15f) * (1.0f / 0.85f);                                       \
    F T2 = 2.0f * tr * tr - 1.0f, T3 = 2.0f * tr * T2 - tr, T4 = 2.0f * tr * T3 - T2, T5 = 2.0f * tr * T4 - T3; \
    F X2 = 2.0f * tx * tx - 1.0f, X3 = 2.0f * tx * X2 - tx, X4 = 2.0f * tx * X3 - X2;                         \
    F X5 = 2.0f * tx * X4 - X3, X6 = 2.0f * tx * X5 - X4;                                                     \
    F e0 = MCL_SHEEN_E_ROW(0.0340701625f, -0.732537372f, -0.176595135f, -0.116232004f, -0.000362558322f, -0.0100314027f); \
    F e1 = MCL_SHEEN_E_ROW(1.30615149f, 1.08928138f, 0.592593401f, 0.0490205127f, 0.0465422549f, -0.00291179853f); \
    F e2 = MCL_SHEEN_E_ROW(-0.571651758f, -0.919286816f, -0.368986737f, -0.0868885307f, -0.0235561057f, -0.00371336469f); \
    F e3 = MCL_SHEEN_E_ROW(0.364110575f, 0.651972149f, 0.236394076f, 0.0581385939f, 0.00953400856f, 0.00284988797f); \
    F e4 = MCL_SHEEN_E_ROW(-0.209488809f, -0.344257596f, -0.125811202f, -0.0232443038f, -0.0060702783f, 0.0011049256f); \
    F e5 = MCL_SHEEN_E_ROW(0.0813096517f, 0.151340521f, 0.0488610999f, 0.00757762893f, 0.000662793935f, 0.000372460702f); \
    F e6 = MCL_SHEEN_E_ROW(-0.0351206088f, -0.0434945922f, -0.0107210722f, 0.00102770199f, -0.000478165875f, 0.00090675683f); \
    F sum = e0 + tx * e1 + X2 * e2 + X3 * e3 + X4 * e4 + X5 * e5 + X6 * e6;                                   \
    return fmax(sum, 0.0f);                                                                                   \
  }                                                                                                           \
  MCL_INLINE F P##sheen_scaling(F3 color, F mu, F r) {                                                        \
    F cmax = fmax(fmax(color.x, color.y), color.z);                                                           \
    return fmin(fmax(1.0f - cmax * P##sheen_albedo(mu, r), 0.0f), 1.0f);                                      \
  }
MCL_DEFINE_SHEEN(, mcl_, float, uint, int, float3, f3, as_uint, as_float, (float))
