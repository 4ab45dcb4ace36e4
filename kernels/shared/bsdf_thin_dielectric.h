// bsdf_thin_dielectric.h: the material kind "thin_dielectric" (material_kinds.h): a thin sheet of
// index ior (a window pane) with two delta lobes: the mirror reflection with the sheet's
// reflectance R' = R + T^2 R / (1 - R^2) (R the single interface's Fresnel reflectance, T = 1 - R,
// the series of internal bounces summed; Mitsuba's thindielectric) and straight-through
// transmission (wi = -wo) with 1 - R', its weight times the tint (white but for glTF's glass:
// its base colour, transmission_tint.h). Both sides alike. Reads a Material's params0.x (ior) and
// .z (tinted by the albedo); pure; compiled by the kernels and the host tests. Written with selects (no early returns).
#pragma once
#include "bsdf_common.h"
#include "transmission_tint.h"

#define MCL_DEFINE_THIN_DIELECTRIC_TYPE(B, F, F3) \
  typedef struct {                                \
    F ior;                                        \
    F3 tint; /* on the transmitted light */       \
  } B;
MCL_DEFINE_THIN_DIELECTRIC_TYPE(ThinDielectricBsdf, float, float3)

// The sheet's reflectance (all inter-reflections: R + T^2 R / (1 - R^2)) and its sample, written once
// for floats and lanes (P, F, F3, M, V: float, float3, int, f3 here; the packet stages' lane types
// in stages/lane_bsdf.h): uLobe < R reflects about ns, else the ray goes straight through; both delta.
#define MCL_DEFINE_THIN_DIELECTRIC(P, F, F3, M, V, B, FR, BS)                                       \
  MCL_INLINE F P##thin_dielectric_reflectance(B b, F cosI) {                                       \
    F cosT;                                                                                        \
    F r = P##fresnel_dielectric(cosI, b.ior, &cosT);                                               \
    F t = 1.0f - r;                                                                                \
    return vsel(r < 1.0f, r + t * t * r / (1.0f - r * r), (F)(1.0f));                              \
  }                                                                                                \
  MCL_INLINE BS P##thin_dielectric_sample(B b, FR s, F3 wo, F u1, F u2, F uLobe) {                 \
    (void)u1;                                                                                      \
    (void)u2;                                                                                      \
    F cosI = V##_dot(wo, s.ns);                                                                    \
    F r = P##thin_dielectric_reflectance(b, fmin(fmax(cosI, 0.0f), 1.0f));                         \
    M refl = uLobe < r;                                                                            \
    BS out;                                                                                        \
    out.wi = V##_select(refl, V##_sub(V##_scale(s.ns, 2.0f * cosI), wo), V##_neg(wo));             \
    M ok = (cosI > 0.0f) & ((V##_dot(s.ng, out.wi) > 0.0f) | (refl == (M)(0)));                    \
    out.pdf = vsel(ok, vsel(refl, r, 1.0f - r), (F)(0.0f));                                        \
    out.weight = V##_select(ok, P##tint_transmitted(b.tint, refl == (M)(0), (F)(1.0f)),           \
                            V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                            \
    out.flags = vsel(refl, (M)(MCL_BSDF_DELTA), (M)(MCL_BSDF_DELTA | MCL_BSDF_TRANSMISSION));      \
    return out;                                                                                    \
  }
MCL_DEFINE_THIN_DIELECTRIC(, float, float3, int, f3, ThinDielectricBsdf, SurfaceFrame, BsdfSample)

MCL_INLINE ThinDielectricBsdf thin_dielectric_from_material(Material m, float3 albedo) {
  ThinDielectricBsdf b;
  b.ior = m.params0.x;
  b.tint = transmission_tint_of(m.params0.z, albedo);
  return b;
}

MCL_INLINE int thin_dielectric_is_delta(ThinDielectricBsdf b) {
  (void)b;
  return 1;
}

MCL_INLINE float3 thin_dielectric_f(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return make_float3(0.0f, 0.0f, 0.0f);
}
MCL_INLINE float3 thin_dielectric_eval(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return make_float3(0.0f, 0.0f, 0.0f);
}
MCL_INLINE float thin_dielectric_pdf(ThinDielectricBsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  (void)b; (void)s; (void)wi; (void)wo;
  return 0.0f;
}

// Written once for floats and lanes (lane_bsdf.h): the albedo AOV, 1 (the sheet passes or
// reflects everything), and the direct integrator's weight: both lobes weigh 1 (each is picked
// with its own reflectance or transmittance), the one through (below the geometric surface) times
// the tint; every direction counts.
#define MCL_DEFINE_THIN_DIELECTRIC_WEIGHTS(P, F, F3, M, V, B, FR)                                       \
  MCL_INLINE F3 P##thin_dielectric_albedo(B b) {                                                        \
    (void)b;                                                                                            \
    return V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f));                                                   \
  }                                                                                                     \
  MCL_INLINE F3 P##thin_dielectric_direction_weight(B b, FR s, F3 wo, F3 wi, F pdf, M* counts) {        \
    (void)wo;                                                                                           \
    (void)pdf;                                                                                          \
    *counts = (F)(0.0f) == (F)(0.0f);                                                                   \
    return P##tint_transmitted(b.tint, (V##_dot(s.ng, wi) > 0.0f) == (M)(0), (F)(1.0f));                \
  }
MCL_DEFINE_THIN_DIELECTRIC_WEIGHTS(, float, float3, int, f3, ThinDielectricBsdf, SurfaceFrame)
