// bsdf.h: the BSDF interface of every shade stage, dispatched on the material kind in one place:
// each function below is a switch generated from the kind table (material_kinds.h) calling the
// kind's own function (bsdf_<kind>.h). Reads nothing but its arguments; pure; compiled by the
// kernels and by the host tests.
//   bsdf_from_material(m, albedo)   the BSDF of device material m at a hit (albedo: textured)
//   bsdf_f(b, s, wo, wi)            f (no cosine), around shading frame s
//   bsdf_eval(b, s, wo, wi)         f * cos(ns, wi)
//   bsdf_pdf(b, s, wo, wi)          solid-angle pdf of bsdf_sample producing wi
//   bsdf_sample(b, s, wo, u1, u2, uLobe)             wi, weight = f cos / pdf, pdf (0: absorbed)
//   bsdf_direction_weight(b, s, wo, wi, pdf)        f cos / p of a sampled direction wi (the
//                                                    direct integrator's split; bsdf_common.h)
//   bsdf_albedo(b)                  the colour of the albedo AOV
//   bsdf_is_delta(b)                1 when every lobe is a delta lobe (a mirror, smooth glass:
//                                   eval and pdf are 0, light sampling there is skipped)
// A tag outside the table (never loaded: the loaders only set tabled kinds) reflects nothing.
// Switches, not function pointers: OpenCL C 1.2 has none; with one kind the switch folds away.
#pragma once
#include "material_kinds.h"
#include "bsdf_diffuse.h"  // one include per kind: bsdf_<kind>.h
#include "bsdf_conductor.h"
#include "bsdf_dielectric.h"
#include "bsdf_thin_dielectric.h"
#include "bsdf_metal_rough.h"
#include "bsdf_coated_diffuse.h"
#include "bsdf_coated_conductor.h"

// A material kind's tag as the device Material holds it (alpha.w, as uint bits).
MCL_INLINE uint material_kind(Material m) { return as_uint(m.alpha.w); }

#define MCL_BSDF_PARAMS_MEMBER(kind, Params) Params kind;
typedef union {
  MCL_MATERIAL_KINDS(MCL_BSDF_PARAMS_MEMBER)
} BsdfParams;
#undef MCL_BSDF_PARAMS_MEMBER

// The BSDF at a hit: the kind and that kind's parameters (p.<kind>).
typedef struct {
  uint kind;
  BsdfParams p;
} Bsdf;

MCL_INLINE Bsdf bsdf_from_material(Material m, float3 albedo) {
  Bsdf b;
  b.kind = material_kind(m);
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: b.p.kind = kind##_from_material(m, albedo); break;
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
    default:  // never read (every function returns its zero for an unknown tag); set, not left undefined
      b.p.diffuse = diffuse_make(make_float3(0.0f, 0.0f, 0.0f), make_float3(0.0f, 0.0f, 0.0f), 1.0f);
  }
  return b;
}

MCL_INLINE float3 bsdf_f(Bsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: return kind##_f(b.p.kind, s, wo, wi);
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  return make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float3 bsdf_eval(Bsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: return kind##_eval(b.p.kind, s, wo, wi);
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  return make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE float bsdf_pdf(Bsdf b, SurfaceFrame s, float3 wo, float3 wi) {
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: return kind##_pdf(b.p.kind, s, wo, wi);
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  return 0.0f;
}

MCL_INLINE BsdfSample bsdf_sample(Bsdf b, SurfaceFrame s, float3 wo, float u1, float u2, float uLobe) {
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: return kind##_sample(b.p.kind, s, wo, u1, u2, uLobe);
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  BsdfSample none;
  none.wi = s.ng;
  none.weight = make_float3(0.0f, 0.0f, 0.0f);
  none.pdf = 0.0f;
  none.flags = 0;
  return none;
}

MCL_INLINE BsdfWeight bsdf_direction_weight(Bsdf b, SurfaceFrame s, float3 wo, float3 wi, float pdf) {
  BsdfWeight w;
  w.weight = make_float3(0.0f, 0.0f, 0.0f);
  w.counts = 0;
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: w.weight = kind##_direction_weight(b.p.kind, s, wo, wi, pdf, &w.counts); break;
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  return w;
}

MCL_INLINE float3 bsdf_albedo(Bsdf b) {
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: return kind##_albedo(b.p.kind);
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  return make_float3(0.0f, 0.0f, 0.0f);
}

MCL_INLINE int bsdf_is_delta(Bsdf b) {
  switch (b.kind) {
#define MCL_BSDF_CASE(kind, Params) \
  case MCL_MATERIAL_##kind: return kind##_is_delta(b.p.kind);
    MCL_MATERIAL_KINDS(MCL_BSDF_CASE)
#undef MCL_BSDF_CASE
  }
  return 0;
}
