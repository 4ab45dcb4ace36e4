// transmission_tint.h: the colour by which the dielectric kinds (bsdf_dielectric.h,
// bsdf_thin_dielectric.h) multiply the light they transmit. glTF's KHR_materials_transmission
// multiplies its specular BTDF by the base colour and leaves the reflection white, so a glass of
// glTF's tints by the hit's albedo (base colour factor x texture x vertex colour, what the frame
// computes), flagged by Material::params0.z > 0 (host/render/device_materials.cpp; the pick of
// transmission_mix.h sets it); the scene file's glass is clear (flag 0, tint 1). Pure; compiled by
// the kernels and the host tests.
#pragma once
#include "lanes.h"

// Written once for floats and lanes (P, F, F3, M, V: the prefix, float, float3, int mask, f3 here;
// the packet stages' v_, vfloat, vfloat3, vmask, v3 in stages/lane_bsdf.h):
// - transmission_tint_of: albedo where the material's flag (params0.z) is set, else white.
// - tint_transmitted: x times the tint where transmitted is set, x alone elsewhere, per channel
//   (x * 1 is x exactly, so clear glass keeps its bits).
#define MCL_DEFINE_TRANSMISSION_TINT(P, F, F3, M, V)                                             \
  MCL_INLINE F3 P##transmission_tint_of(F flag, F3 albedo) {                                     \
    return V##_select(flag > 0.0f, albedo, V##_make((F)(1.0f), (F)(1.0f), (F)(1.0f)));           \
  }                                                                                              \
  MCL_INLINE F3 P##tint_transmitted(F3 tint, M transmitted, F x) {                               \
    return V##_make(x * vsel(transmitted, tint.x, (F)(1.0f)), x * vsel(transmitted, tint.y, (F)(1.0f)), \
                    x * vsel(transmitted, tint.z, (F)(1.0f)));                                   \
  }
MCL_DEFINE_TRANSMISSION_TINT(, float, float3, int, f3)
