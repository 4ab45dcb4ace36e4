// environment.h: the environment light: radiance arriving from infinitely far away in direction
// -dir for a ray travelling along dir that escapes the scene. Either a constant (FrameParams
// environment.rgb; envWidth = 0) or that constant times a latitude-longitude map of
// envWidth x envHeight texels (envMap: rgb radiance, w = the texel's density p(u, v) of the
// sampling distribution below), rotated about +y by envRotateY.
// Map convention (Mitsuba 3's envmap): texel (u, v) in [0, 1)^2, row v = 0 at the top (+y);
// theta = pi v from +y, phi = 2 pi u, direction (sin theta sin phi, cos theta, -sin theta cos phi).
// Lookups are nearest-texel (piecewise constant), so the sampling density is exactly proportional
// to the luminance of what is looked up.
// Importance sampling (pbrt's Distribution2D): p(u, v) proportional to luminance * sin(theta) of
// the texel, drawn as a marginal over rows then a conditional within the row; envCdf holds the
// marginal CDF (envHeight + 1 floats) followed by each row's CDF (envWidth + 1 floats per row),
// built by host/render/environment_table.cpp. Solid-angle pdf = p(u, v) / (2 pi^2 sin theta).
// A constant environment is sampled uniformly over the sphere (pdf 1 / (4 pi)).
// Light selection: a light sample goes to the environment with probability
// env_pick_probability = FrameParams::shareEnvironment: 1 without other lights, else its share of
// the lights' power (host/render/light_table.cpp). Pure; compiled by the kernels and by the host tests.
#pragma once
#include "lights.h"
#include "sampling.h"
#include "trig.h"

#define MCL_INV_4PI 0.07957747154594766788f
#define MCL_INV_2PI2 0.05066059182116888572f  // 1 / (2 pi^2)

MCL_INLINE int env_present(MCL_CONSTANT const FrameParams* f) { return f->environment.w != 0.0f; }

MCL_INLINE float env_pick_probability(MCL_CONSTANT const FrameParams* f) {
  return env_present(f) ? f->shareEnvironment : 0.0f;
}

// The functions below are written once for floats and lanes: P, F, F3, U, M, V (the prefix, float,
// float3, uint, int mask and f3 here; v_, vfloat, vfloat3, vuint, vmask, v3 in
// stages/lane_lights.h), ES the sample's type, S the portable trigonometry's prefix, G the
// prefix of the table reads (G##gather_float, G##load_float4: one element per lane), ANY a mask's
// any, CVT_U_F float to uint, CVT_F_U uint to float, AS_U a float's bits. Each lane does the float
// function's operations in the same order (the same bits), and the map's coordinates come from the
// portable atan2 and acos (trig.h), so every device finds the same texel.
#define MCL_DEFINE_ENV_SAMPLE_TYPE(T, F, F3) \
  typedef struct {                           \
    F3 wi; /* direction toward the environment (unit) */ \
    F3 le; /* radiance arriving from it */   \
    F pdf; /* solid angle; 0: no sample */   \
  } T;
MCL_DEFINE_ENV_SAMPLE_TYPE(EnvSample, float, float3)

MCL_INLINE float4 mcl_load_float4(MCL_GLOBAL const float4* p, uint i) { return p[i]; }

#define MCL_DEFINE_ENVIRONMENT(P, F, F3, F4, U, M, V, ES, S, G, ANY, CVT_U_F, CVT_F_U, AS_U)                 \
  /* d rotated by angle a (radians) about +y (right-handed). */                                            \
  MCL_INLINE F3 P##rotate_about_y(F3 d, float a) {                                                          \
    float s, c;                                                                                             \
    mcl_sincos_turns(a * MCL_INV_2PI, &s, &c);                                                              \
    return V##_make(c * d.x + s * d.z, d.y, c * d.z - s * d.x);                                            \
  }                                                                                                         \
  /* Map coordinates of a unit direction in the map's frame. */                                             \
  MCL_INLINE void P##env_uv_of(F3 d, F* u, F* v) {                                                          \
    F x = S##atan2(d.x, -d.z) * MCL_INV_2PI;                                                                \
    *u = vsel(x < 0.0f, x + 1.0f, x);                                                                       \
    *v = S##acos(fmin(fmax(d.y, -1.0f), 1.0f)) * MCL_INV_PI;                                                \
  }                                                                                                         \
  MCL_INLINE U P##env_texel_of(F u, F v, uint width, uint height) {                                         \
    U x = CVT_U_F(u * (float)width), y = CVT_U_F(v * (float)height);                                       \
    x = vsel(x < width, x, (U)(width - 1u));                                                                \
    y = vsel(y < height, y, (U)(height - 1u));                                                              \
    return y * width + x;                                                                                   \
  }                                                                                                         \
  /* Radiance arriving along -dir (dir: the escaping ray's direction, unit). */                             \
  MCL_INLINE F3 P##env_radiance(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* map, F3 dir) {  \
    float3 e = xyz(f->environment);                                                                         \
    if (f->envWidth == 0u) return V##_make((F)(e.x), (F)(e.y), (F)(e.z));                                  \
    F u, v;                                                                                                 \
    P##env_uv_of(P##rotate_about_y(dir, -f->envRotateY), &u, &v);                                           \
    F4 t = G##load_float4(map, P##env_texel_of(u, v, f->envWidth, f->envHeight));                           \
    return V##_make(e.x * t.x, e.y * t.y, e.z * t.z);                                                       \
  }                                                                                                         \
  /* Solid-angle pdf of env_sample producing dir (not including env_pick_probability). */                   \
  MCL_INLINE F P##env_pdf(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* map, F3 dir) {        \
    if (f->envWidth == 0u) return (F)(MCL_INV_4PI);                                                         \
    F3 d = P##rotate_about_y(dir, -f->envRotateY);                                                          \
    F sinTheta = sqrt(d.x * d.x + d.z * d.z); /* not from d.y: precise near the poles */                    \
    F u, v;                                                                                                 \
    P##env_uv_of(d, &u, &v);                                                                                \
    F4 t = G##load_float4(map, P##env_texel_of(u, v, f->envWidth, f->envHeight));                           \
    return vsel(sinTheta > 0.0f, t.w * MCL_INV_2PI2 / sinTheta, (F)(0.0f));                                 \
  }                                                                                                         \
  /* Largest i in [0, n - 1] with cdf[at + i] <= u (cdf[at] = 0 <= u < 1 = cdf[at + n]): skips empty       \
     intervals. */                                                                                          \
  MCL_INLINE U P##env_cdf_find(MCL_GLOBAL const float* cdf, U at, uint n, F u) {                            \
    U lo = (U)(0u), hi = (U)(n - 1u);                                                                       \
    for (;;) {                                                                                              \
      M on = lo < hi;                                                                                       \
      if (!ANY(on)) break;                                                                                  \
      U mid = (lo + hi + 1u) / 2u;                                                                          \
      M below = G##gather_float(cdf, at + vsel(on, mid, lo), 1u) <= u;                                            \
      M none = below == (M)(0);                                                                             \
      lo = vsel(on & below, mid, lo);                                                                       \
      hi = vsel(on & none, mid - 1u, hi);                                                                   \
    }                                                                                                       \
    return lo;                                                                                              \
  }                                                                                                         \
  MCL_INLINE ES P##env_sample(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* map,              \
                              MCL_GLOBAL const float* cdf, F u1, F u2) {                                    \
    ES s;                                                                                                   \
    float3 e = xyz(f->environment);                                                                         \
    if (f->envWidth == 0u) { /* uniform over the sphere */                                                  \
      F y = 1.0f - 2.0f * u2;                                                                               \
      F r = 2.0f * sqrt(u2 * (1.0f - u2)); /* sqrt(1 - y^2), without cancellation */                        \
      F sinPhi, cosPhi;                                                                                     \
      S##sincos_turns(u1, &sinPhi, &cosPhi);                                                                \
      s.wi = V##_make(r * sinPhi, y, -r * cosPhi);                                                          \
      s.le = V##_make((F)(e.x), (F)(e.y), (F)(e.z));                                                        \
      s.pdf = (F)(MCL_INV_4PI);                                                                             \
      return s;                                                                                             \
    }                                                                                                       \
    const uint w = f->envWidth, h = f->envHeight;                                                           \
    U j = P##env_cdf_find(cdf, (U)(0u), h, u2);                                                             \
    F c0 = G##gather_float(cdf, j, 1u), c1 = G##gather_float(cdf, j + 1u, 1u);                                          \
    F dv = vsel(c1 > c0, (u2 - c0) / (c1 - c0), (F)(0.5f));                                                 \
    U row = (h + 1u) + j * (w + 1u);                                                                        \
    U i = P##env_cdf_find(cdf, row, w, u1);                                                                 \
    F r0 = G##gather_float(cdf, row + i, 1u), r1 = G##gather_float(cdf, row + i + 1u, 1u);                              \
    F du = vsel(r1 > r0, (u1 - r0) / (r1 - r0), (F)(0.5f));                                                 \
    F sinTheta, cosTheta, sinPhi, cosPhi;                                                                   \
    S##sincos_turns(0.5f * ((CVT_F_U(j) + dv) / (float)h), &sinTheta, &cosTheta); /* theta = pi v */        \
    S##sincos_turns((CVT_F_U(i) + du) / (float)w, &sinPhi, &cosPhi);              /* phi = 2 pi u */        \
    sinTheta = fmax(sinTheta, 0.0f);                                                                        \
    F3 d = V##_make(sinTheta * sinPhi, cosTheta, -sinTheta * cosPhi);                                       \
    s.wi = P##rotate_about_y(d, f->envRotateY);                                                             \
    F4 t = G##load_float4(map, j * w + i);                                                                  \
    s.le = V##_make(e.x * t.x, e.y * t.y, e.z * t.z);                                                       \
    s.pdf = vsel(sinTheta > 0.0f, t.w * MCL_INV_2PI2 / sinTheta, (F)(0.0f));                                \
    return s;                                                                                               \
  }
MCL_DEFINE_ENVIRONMENT(, float, float3, float4, uint, int, f3, EnvSample, mcl_, mcl_, MCL_ANY1, (uint), (float), as_uint)

MCL_INLINE float2 env_dir_to_uv(float3 d) {
  float u, v;
  env_uv_of(d, &u, &v);
  return make_float2(u, v);
}

MCL_INLINE uint env_texel(float2 uv, uint width, uint height) { return env_texel_of(uv.x, uv.y, width, height); }
