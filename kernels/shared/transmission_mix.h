// transmission_mix.h: a partly transmissive metal_rough material (glTF KHR_materials_transmission
// with a factor t in (0, 1), or metallic > 0): reads the Material's params0 (x: metallic, y:
// roughness, after the metallic-roughness texture) and params1 (x: t, y: ior, z: 1 for a solid
// dielectric, 0 for a thin sheet; host/render/device_materials.cpp) and returns the Material of
// one of two kinds, picked per hit (by a number from the frame's sampler). Pure; compiled by the
// kernels and the host tests.
// t is the factor times the transmissionTexture's R at the hit (surface_texture.h
// hit_transmission_texture; params1.w: that texture + 1, 0 none).
// glTF's BSDF is metallic x metal + (1 - metallic) x fresnel_mix(specular, mix(diffuse, btdf, t)).
// With p = t (1 - metallic) it is exactly p x (the dielectric: Fresnel-weighted specular + btdf) +
// (1 - p) x metal_rough(metallic / (1 - p)) (the same metal weight, the rest Lambert + specular),
// so the hit becomes the (thin_)dielectric kind (ior, alpha = roughness^2; thin: smooth; its
// transmission tinted by the base colour, glTF's btdf x baseColor: transmission_tint.h) with
// probability p, else metal_rough with metallic / (1 - p): a stochastic choice of one kind,
// unbiased, branch-free, and every stage keeps seeing one kind (delta or not) per hit. The number
// deciding it is a pure function of the sample and the bounce (SampleRef), so every stage that
// rebuilds the surface of the same hit (shade_direct and shade_direct_hit, record_aov) makes the
// same choice: under the Sobol sampler a dimension of the sample's own (group MCL_DIM_MIX + bounce),
// so a pixel's N samples pick the glass close to p N times (within the sub-sequence count K: each
// scrambled sub-sequence puts one point in each of its 2^m intervals), not binomially; under the
// independent sampler a hash of the hit itself (triangle, barycentrics, ray direction), i.i.d.
#pragma once
#include "material_kinds.h"
#include "rng.h"
#include "sampler.h"
#include "types.h"

// The kind's pick written once for floats and lanes (P, F, U, M, F3: the prefix, float, uint, int
// mask, float3 here; the packet stages' v_, vfloat, vuint, vmask, vfloat3 in stage_lanes.h, with
// mix32 MIX, the float -> uint bit cast AS_U and u32_to_unit UNIT).
// - hit_uniform_at: a uniform number in [0, 1) that is a function of the hit (triangle tri,
//   barycentrics u, v) of a ray along dir.
// - transmission_pick: the kind a material of kind `kind` with transmission factor t (params1.x),
//   index ior (params1.y) and solid flag (params1.z) is at a hit whose uniform number is u (only
//   read where the material mixes); *metallic, *roughness, *tinted (params0.x, .y, .z in, the
//   picked kind's params0.x, .y, .z out: the glass is tinted by the albedo).
#define MCL_DEFINE_TRANSMISSION_PICK(P, F, U, M, F3, MIX, AS_U, UNIT)                           \
  MCL_INLINE F P##hit_uniform_at(U tri, F u, F v, F3 dir) {                                     \
    U x = MIX(tri ^ 0x9e3779b9u);                                                               \
    x = MIX(x ^ AS_U(u));                                                                       \
    x = MIX(x ^ AS_U(v));                                                                       \
    x = MIX(x ^ AS_U(dir.x));                                                                   \
    x = MIX(x ^ AS_U(dir.y));                                                                   \
    x = MIX(x ^ AS_U(dir.z));                                                                   \
    return UNIT(x);                                                                             \
  }                                                                                             \
  MCL_INLINE U P##transmission_pick(U kind, F t, F ior, F solidFlag, F u, F* metallic, F* roughness,  \
                                    F* tinted) {                                                \
    M mixes = (kind == (uint)MCL_MATERIAL_metal_rough) & (t > 0.0f);                            \
    F p = t * (1.0f - *metallic);                                                               \
    M pick = mixes & (u < p);                                                                   \
    M solid = solidFlag > 0.0f;                                                                 \
    U glass = vsel(solid, (U)((uint)MCL_MATERIAL_dielectric), (U)((uint)MCL_MATERIAL_thin_dielectric)); \
    F rest = fmin(*metallic / fmax(1.0f - p, 1e-30f), 1.0f);                                    \
    F r = *roughness;                                                                           \
    *metallic = vsel(pick, ior, vsel(mixes, rest, *metallic));                                  \
    *roughness = vsel(pick, vsel(solid, r * r, (F)(0.0f)), r);                                  \
    *tinted = vsel(pick, (F)(1.0f), *tinted);                                                   \
    return vsel(pick, glass, kind);                                                             \
  }
MCL_DEFINE_TRANSMISSION_PICK(, float, uint, int, float3, mcl_mix32, as_uint, u32_to_unit)

// A uniform number in [0, 1) that is a function of the hit h of a ray along dir.
MCL_INLINE float hit_uniform(Hit h, float3 dir) { return hit_uniform_at(h.tri, h.u, h.v, dir); }

// Which sample a surface is built for: its pixel, its sample index and the bounce (0: the camera
// ray's hit).
typedef struct {
  uint pixel, sample, bounce;
} SampleRef;

MCL_INLINE SampleRef sample_ref(uint pixel, uint sample, uint bounce) {
  SampleRef r;
  r.pixel = pixel;
  r.sample = sample;
  r.bounce = bounce;
  return r;
}

// The uniform number that picks the kind for sample r's hit h of a ray along dir (above).
MCL_INLINE float transmission_uniform(MCL_CONSTANT const FrameParams* f, SampleRef r, Hit h, float3 dir) {
  if (f->sampler == MCL_SAMPLER_SOBOL) return sample_uniform4(f, r.pixel, r.sample, MCL_DIM_MIX + r.bounce).x;
  return hit_uniform(h, dir);
}

// m itself unless it is a metal_rough material with a transmission factor > 0 (so every other
// material, and every metal_rough one without transmission, keeps its bits and draws no number).
MCL_INLINE Material hit_transmission(MCL_CONSTANT const FrameParams* f, Material m, SampleRef r, Hit h, float3 dir) {
  uint kind = as_uint(m.alpha.w);
  int mixes = kind == (uint)MCL_MATERIAL_metal_rough && m.params1.x > 0.0f;
  float u = mixes ? transmission_uniform(f, r, h, dir) : 1.0f;
  float metallic = m.params0.x, roughness = m.params0.y, tinted = m.params0.z;
  Material out = m;
  out.alpha.w =
      as_float(transmission_pick(kind, m.params1.x, m.params1.y, m.params1.z, u, &metallic, &roughness, &tinted));
  out.params0.x = metallic;
  out.params0.y = roughness;
  out.params0.z = tinted;
  return out;
}
