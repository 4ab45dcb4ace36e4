// integrands.h: the built-in integrands of `montecl integrate` and one sample of each estimator
// (rectangle/midpoint rule, uniform Monte Carlo, importance sampling), as pure functions compiled
// both by kernels/integrate.cl and by the C++ tests. Every function returns one term whose mean
// over the N samples is the estimate: f(x_i) * volume for the midpoint rule and uniform MC,
// f(x_i) / p(x_i) for importance sampling.
#pragma once
#include "compat.h"
#include "rng.h"

#define MCL_INTEGRAND_SINE 0u
#define MCL_INTEGRAND_SMOOTH2D 1u

#define MCL_EST_RECTANGLE 0u
#define MCL_EST_MC_UNIFORM 1u
#define MCL_EST_MC_IMPORTANCE 2u

#define MCL_TWO_PI_F 6.28318530717958647692f

// --- sine: f(x) = 1 + cos(2 pi k x) on [0, 1], exact integral 1 for every integer k >= 1 --------
// f depends only on the phase t = frac(k x), which the samplers compute exactly in integers, so a
// large k loses no precision in float. With k = N the midpoint rule hits t = 1/2 at every point
// (f = 0): far above Nyquist (N/2), every box underestimates and the estimate is 0.
MCL_INLINE float mcl_sine_f(float t) { return 1.0f + cos(MCL_TWO_PI_F * t); }

// Importance pdf (per unit length) p(x) = 1 + B cos(2 pi k x): close to f, positive, normalised.
#define MCL_SINE_IS_B 0.8f
MCL_INLINE float mcl_sine_pdf(float t) { return 1.0f + MCL_SINE_IS_B * cos(MCL_TWO_PI_F * t); }

// Phase t in [0, 1) with density mcl_sine_pdf, by inverting F(t) = t + B sin(2 pi t) / (2 pi) with
// safeguarded Newton steps. Every period of p holds the same mass 1/k, so the period itself (which
// f/p does not depend on) needs no sampling.
MCL_INLINE float mcl_sine_sample_phase(float u) {
  float lo = 0.0f, hi = 1.0f, t = u;
  for (int it = 0; it < 40; ++it) {
    float F = t + MCL_SINE_IS_B * sin(MCL_TWO_PI_F * t) * (1.0f / MCL_TWO_PI_F) - u;
    if (F > 0.0f) hi = t; else lo = t;
    if (fabs(F) < 1e-7f) break;
    float tn = t - F / mcl_sine_pdf(t);
    t = (tn > lo && tn < hi) ? tn : 0.5f * (lo + hi);
  }
  return t;
}

// --- smooth2d over [-0.1, 1.2]^2 (the lecture's domain) ---------------------------------------
// f(x, y) = exp(1.5 x) (1 + y + y^2) + 3 exp(-((x - 0.7)^2 + (y - 0.3)^2) / 0.08)
// exact integral (host, double): a product of closed forms plus a product of two erf differences.
#define MCL_S2D_LO (-0.1f)
#define MCL_S2D_HI 1.2f
MCL_INLINE float mcl_smooth2d_f(float x, float y) {
  float dx = x - 0.7f, dy = y - 0.3f;
  return exp(1.5f * x) * (1.0f + y + y * y) + 3.0f * exp(-(dx * dx + dy * dy) * (1.0f / 0.08f));
}

// Importance pdf: product of two linear densities a + b x on [lo, hi] fitted to exp(1.5 x) and to
// 1 + y + y^2 (the bump is ignored), each sampled by inverting its quadratic CDF.
#define MCL_S2D_AX 0.6f
#define MCL_S2D_BX 3.75f
#define MCL_S2D_AY 0.85f
#define MCL_S2D_BY 2.1f
MCL_INLINE float mcl_linear_norm(float a, float b) {
  return a * (MCL_S2D_HI - MCL_S2D_LO) + 0.5f * b * (MCL_S2D_HI * MCL_S2D_HI - MCL_S2D_LO * MCL_S2D_LO);
}
MCL_INLINE float mcl_linear_pdf(float a, float b, float x) { return (a + b * x) / mcl_linear_norm(a, b); }
// Solves (a (x - lo) + b (x^2 - lo^2) / 2) / Z = u for x in the cancellation-free form.
MCL_INLINE float mcl_linear_sample(float a, float b, float u) {
  float z = mcl_linear_norm(a, b);
  float c = a + b * MCL_S2D_LO;
  float x = MCL_S2D_LO + 2.0f * u * z / (c + sqrt(c * c + 2.0f * b * u * z));
  return fmin(fmax(x, MCL_S2D_LO), MCL_S2D_HI);
}

// --- one estimator term ---------------------------------------------------------------------
// i: sample index in [0, n); gridX: midpoint grid width for 2D (n = gridX * gridY); seed: run
// index (counter-based RNG: the term is a pure function of its arguments); k: sine frequency.
MCL_INLINE float mcl_integrate_term(uint integrand, uint estimator, uint i, uint n, uint gridX, uint seed,
                                    uint k) {
  RngOut r = pcg4d(i, estimator, integrand, seed);
  if (integrand == MCL_INTEGRAND_SINE) {
    if (estimator == MCL_EST_RECTANGLE) {
      // midpoint x = (i + 1/2) / n, phase frac(k x) = ((2i + 1) k mod 2n) / 2n, exactly
      ulong num = ((2ul * (ulong)i + 1ul) * (ulong)k) % (2ul * (ulong)n);
      return mcl_sine_f((float)num / (float)(2ul * (ulong)n));  // volume 1
    }
    if (estimator == MCL_EST_MC_UNIFORM) {
      // x = m / 2^24 (24 random bits); frac(k x) = (k m mod 2^24) / 2^24 exactly
      uint m = r.x >> 8;
      float t = (float)((m * k) & 0xFFFFFFu) * (1.0f / 16777216.0f);
      return mcl_sine_f(t);  // volume 1
    }
    float t = mcl_sine_sample_phase(u32_to_unit(r.x));
    return mcl_sine_f(t) / mcl_sine_pdf(t);
  }
  // smooth2d
  float ext = MCL_S2D_HI - MCL_S2D_LO;
  if (estimator == MCL_EST_RECTANGLE) {
    uint gridY = n / gridX;
    uint ix = i % gridX, iy = i / gridX;
    float x = MCL_S2D_LO + ext * ((float)ix + 0.5f) / (float)gridX;
    float y = MCL_S2D_LO + ext * ((float)iy + 0.5f) / (float)gridY;
    return mcl_smooth2d_f(x, y) * ext * ext;
  }
  if (estimator == MCL_EST_MC_UNIFORM) {
    float x = MCL_S2D_LO + ext * u32_to_unit(r.x);
    float y = MCL_S2D_LO + ext * u32_to_unit(r.y);
    return mcl_smooth2d_f(x, y) * ext * ext;  // f / p with p = 1 / area
  }
  float x = mcl_linear_sample(MCL_S2D_AX, MCL_S2D_BX, u32_to_unit(r.x));
  float y = mcl_linear_sample(MCL_S2D_AY, MCL_S2D_BY, u32_to_unit(r.y));
  return mcl_smooth2d_f(x, y) / (mcl_linear_pdf(MCL_S2D_AX, MCL_S2D_BX, x) * mcl_linear_pdf(MCL_S2D_AY, MCL_S2D_BY, y));
}
