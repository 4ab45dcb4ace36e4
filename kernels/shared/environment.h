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

// d rotated by angle a (radians) about +y (right-handed).
MCL_INLINE float3 rotate_about_y(float3 d, float a) {
  float s, c;
  mcl_sincos_turns(a * MCL_INV_2PI, &s, &c);
  return make_float3(c * d.x + s * d.z, d.y, c * d.z - s * d.x);
}

// Map coordinates of a unit direction in the map's frame.
MCL_INLINE float2 env_dir_to_uv(float3 d) {
  float u = atan2(d.x, -d.z) * MCL_INV_2PI;
  if (u < 0.0f) u += 1.0f;
  float v = acos(fmin(fmax(d.y, -1.0f), 1.0f)) * MCL_INV_PI;
  return make_float2(u, v);
}

MCL_INLINE uint env_texel(float2 uv, uint width, uint height) {
  uint x = (uint)(uv.x * (float)width), y = (uint)(uv.y * (float)height);
  x = x < width ? x : width - 1;
  y = y < height ? y : height - 1;
  return y * width + x;
}

// Radiance arriving along -dir (dir: the escaping ray's direction, unit).
MCL_INLINE float3 env_radiance(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* map, float3 dir) {
  float3 e = xyz(f->environment);
  if (f->envWidth == 0u) return e;
  float2 uv = env_dir_to_uv(rotate_about_y(dir, -f->envRotateY));
  return e * xyz(map[env_texel(uv, f->envWidth, f->envHeight)]);
}

// Solid-angle pdf of env_sample producing dir (not including env_pick_probability).
MCL_INLINE float env_pdf(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* map, float3 dir) {
  if (f->envWidth == 0u) return MCL_INV_4PI;
  float3 d = rotate_about_y(dir, -f->envRotateY);
  float sinTheta = sqrt(d.x * d.x + d.z * d.z);  // not from d.y: precise near the poles
  if (!(sinTheta > 0.0f)) return 0.0f;
  return map[env_texel(env_dir_to_uv(d), f->envWidth, f->envHeight)].w * MCL_INV_2PI2 / sinTheta;
}

// Largest i in [0, n - 1] with cdf[i] <= u (cdf[0] = 0 <= u < 1 = cdf[n]): skips empty intervals.
MCL_INLINE uint env_cdf_find(MCL_GLOBAL const float* cdf, uint n, float u) {
  uint lo = 0, hi = n - 1;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (cdf[mid] <= u) lo = mid;
    else hi = mid - 1u;
  }
  return lo;
}

typedef struct {
  float3 wi;   // direction toward the environment (unit)
  float3 le;   // radiance arriving from it
  float pdf;   // solid angle; 0: no sample
} EnvSample;

MCL_INLINE EnvSample env_sample(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const float4* map,
                                MCL_GLOBAL const float* cdf, float u1, float u2) {
  EnvSample s;
  if (f->envWidth == 0u) {  // uniform over the sphere
    float y = 1.0f - 2.0f * u2;
    float r = 2.0f * sqrt(u2 * (1.0f - u2));  // sqrt(1 - y^2), without cancellation
    float sinPhi, cosPhi;
    mcl_sincos_turns(u1, &sinPhi, &cosPhi);
    s.wi = make_float3(r * sinPhi, y, -r * cosPhi);
    s.le = xyz(f->environment);
    s.pdf = MCL_INV_4PI;
    return s;
  }
  uint w = f->envWidth, h = f->envHeight;
  uint j = env_cdf_find(cdf, h, u2);
  float c0 = cdf[j], c1 = cdf[j + 1u];
  float dv = c1 > c0 ? (u2 - c0) / (c1 - c0) : 0.5f;
  MCL_GLOBAL const float* row = cdf + (h + 1u) + j * (w + 1u);
  uint i = env_cdf_find(row, w, u1);
  float r0 = row[i], r1 = row[i + 1u];
  float du = r1 > r0 ? (u1 - r0) / (r1 - r0) : 0.5f;
  float sinTheta, cosTheta, sinPhi, cosPhi;
  mcl_sincos_turns(0.5f * (((float)j + dv) / (float)h), &sinTheta, &cosTheta);  // theta = pi v
  mcl_sincos_turns(((float)i + du) / (float)w, &sinPhi, &cosPhi);               // phi = 2 pi u
  sinTheta = fmax(sinTheta, 0.0f);
  float3 d = make_float3(sinTheta * sinPhi, cosTheta, -sinTheta * cosPhi);
  s.wi = rotate_about_y(d, f->envRotateY);
  float4 t = map[j * w + i];
  s.le = xyz(f->environment) * xyz(t);
  s.pdf = sinTheta > 0.0f ? t.w * MCL_INV_2PI2 / sinTheta : 0.0f;
  return s;
}
