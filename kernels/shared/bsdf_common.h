// bsdf_common.h: what every material kind's BSDF file (bsdf_<kind>.h) returns and uses: the sample
// structs of the BSDF interface and local coordinates around a normal. Pure; compiled by the
// kernels and by the host tests.
// Conventions of the interface (shared/bsdf.h): wo points from the surface toward the viewer, wi
// toward the light, both unit; directions are taken around a shading frame (shared/shading.h).
#pragma once
#include "lights.h"
#include "sampling.h"
#include "shading.h"

// Lobe flags of a sample (as pbrt's BSDFFlags): a sample from a delta lobe (a mirror, smooth glass)
// has no solid-angle density: its pdf is the discrete probability of the lobe that was picked, its
// weight the exact f cos / p of that lobe, and <kind>_eval / _pdf give 0 for every direction (a
// light sample can never land on it). The integrators skip MIS after such a bounce (the emitter or
// environment it finds counts fully) and skip light sampling at a surface that is purely delta
// (<kind>_is_delta). A transmitted sample leaves below the geometric surface: its ray starts on
// that side (the ray-origin offset follows it).
#define MCL_BSDF_DELTA 1
#define MCL_BSDF_TRANSMISSION 2

// A direction drawn by <kind>_sample with its weight: wi; weight f * cos / pdf; pdf, in solid angle
// (delta: the lobe's discrete probability), 0: no direction (absorbed); flags MCL_BSDF_DELTA |
// MCL_BSDF_TRANSMISSION, 0 for a non-delta reflection. Declared once for floats and lanes (the
// packet stages' vBsdfSample, stages/lane_bsdf.h).
#define MCL_DEFINE_BSDF_SAMPLE_TYPE(T, F, F3, M) \
  typedef struct {                               \
    F3 wi;                                       \
    F3 weight;                                   \
    F pdf;                                       \
    M flags;                                     \
  } T;
MCL_DEFINE_BSDF_SAMPLE_TYPE(BsdfSample, float, float3, int)

// The direct integrator draws its BSDF direction in shade_direct (the kind's sample, traced where
// its pdf is positive; the Lambertian lobe: the cosine lobe, folded above the geometric surface,
// always traced) and weighs it in shade_direct_hit, with only the direction passed between them:
// <kind>_direction_weight gives the f cos / p of that direction (counts 0: it contributes nothing,
// the slot stays 0). For a kind whose sample weight is simply eval / pdf that is eval * (1 / pdf)
// with pdf > 0.
typedef struct {
  float3 weight;  // f * cos / pdf
  int counts;
} BsdfWeight;

// The ray origin for a ray leaving a hit at p (geometric normal ng facing the incoming ray) with
// sample flags `flags`: offset to ng's side, or to the other side for a transmitted ray.
MCL_INLINE float3 bsdf_ray_origin(float3 p, float3 ng, int flags, float scale) {
  return offset_ray_origin(p, (flags & MCL_BSDF_TRANSMISSION) ? -ng : ng, scale);
}

// Written once for floats and lanes (F, F3, V: float, float3, f3 here; vfloat, vfloat3, v3 in
// stages/lane_bsdf.h), selects rather than branches:
// - fresnel_dielectric: the unpolarised Fresnel reflectance of a dielectric interface for cosI =
//   cos of the incident angle (> 0, on the side of the incident medium) and eta = n_transmitted /
//   n_incident; *cosT receives the cosine of the refracted direction (0 under total internal
//   reflection, where R = 1).
// - fresnel_conductor1: the unpolarised Fresnel reflectance of a conductor of complex index
//   eta + i k (relative to the outside medium) for one channel at cosI in [0, 1]: the exact
//   expression (e.g. pbrt-v3's FrConductor); fresnel_conductor: per RGB channel.
// - to_local: the local coordinates of w in the frame (t, b, n) of make_basis.
// - over_cosine: a kind's f from its f cos: fcos / c where the cosine c is positive, else 0.
#define MCL_DEFINE_FRESNEL(P, F, F3, V)                                                  \
  MCL_INLINE F P##fresnel_dielectric(F cosI, F eta, F* cosT) {                          \
    F sin2T = (1.0f - cosI * cosI) / (eta * eta);                                        \
    F c = sqrt(fmax((F)(0.0f), 1.0f - sin2T));                                           \
    F rs = (cosI - eta * c) / (cosI + eta * c);                                          \
    F rp = (eta * cosI - c) / (eta * cosI + c);                                          \
    *cosT = vsel(sin2T >= 1.0f, (F)(0.0f), c);                                           \
    return vsel(sin2T >= 1.0f, (F)(1.0f), 0.5f * (rs * rs + rp * rp));                   \
  }                                                                                      \
  MCL_INLINE F P##fresnel_conductor1(F cosI, F eta, F k) {                              \
    F c2 = cosI * cosI, s2 = 1.0f - c2;                                                  \
    F e2 = eta * eta, k2 = k * k;                                                        \
    F t0 = e2 - k2 - s2;                                                                 \
    F a2b2 = sqrt(fmax((F)(0.0f), t0 * t0 + 4.0f * e2 * k2));                            \
    F a = sqrt(fmax((F)(0.0f), 0.5f * (a2b2 + t0)));                                     \
    F t1 = a2b2 + c2, t2 = 2.0f * cosI * a;                                              \
    F rs = (t1 - t2) / fmax(t1 + t2, 1e-30f);                                            \
    F t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;                                            \
    F rp = rs * (t3 - t4) / fmax(t3 + t4, 1e-30f);                                       \
    return 0.5f * (rs + rp);                                                             \
  }                                                                                      \
  MCL_INLINE F3 P##fresnel_conductor(F cosI, F3 eta, F3 k) {                            \
    return V##_make(P##fresnel_conductor1(cosI, eta.x, k.x), P##fresnel_conductor1(cosI, eta.y, k.y), \
                    P##fresnel_conductor1(cosI, eta.z, k.z));                            \
  }                                                                                      \
  MCL_INLINE F3 P##to_local(F3 w, F3 n) {                                               \
    F3 t, b;                                                                             \
    P##make_basis(n, &t, &b);                                                            \
    return V##_make(V##_dot(w, t), V##_dot(w, b), V##_dot(w, n));                        \
  }                                                                                      \
  MCL_INLINE F3 P##over_cosine(F3 fcos, F c) {                                          \
    return V##_select(c > 0.0f, V##_scale(fcos, 1.0f / c), V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f))); \
  }
MCL_DEFINE_FRESNEL(, float, float3, f3)
