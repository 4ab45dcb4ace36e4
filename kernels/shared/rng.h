// rng.h: counter-based random numbers. Every number is a pure function of
// (seed, pixel, sample index, dimension), so images do not depend on wave size, work-group size,
// scheduling or device. pcg4d (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020)
// is a bijection on 128 bits: distinct inputs never share their four outputs.
#pragma once
#include "compat.h"

// Dimensions are drawn in groups of four; each stage owns a fixed group.
#define MCL_DIM_CAMERA 0u     // pixel jitter u, v
#define MCL_DIM_AO 1u         // AO direction
#define MCL_DIM_LIGHT 2u      // direct lighting: light choice and point (+ k per extra light sample)
#define MCL_DIM_BRDF 1u       // direct lighting: BRDF direction (shares AO's group; never both)
#define MCL_DIM_LENS 0x7fffffffu  // thin lens: point on the aperture (x, y)
// Path tracing: bounce b owns groups MCL_DIM_PATH + b * MCL_DIM_PATH_STRIDE + j: j = 0 the BSDF
// direction (x, y), Russian roulette (z) and the BSDF lobe (w); j = 1 + k light sample k (as
// MCL_DIM_LIGHT + k).
#define MCL_DIM_PATH 0x80000000u
// The choice between a partly transmissive material's two kinds at bounce b (0: the camera hit;
// shared/transmission_mix.h) owns group MCL_DIM_MIX + b (x), under the Sobol sampler only.
#define MCL_DIM_MIX 0x40000000u
#define MCL_DIM_PATH_STRIDE 1025u  // 1 + the most light samples (kMaxLightSamples)

typedef struct {
  uint x, y, z, w;
} RngOut;

// Written once for any unsigned 32-bit type T and its four-tuple Out (uint and RngOut here; the
// packet stages' vuint lanes and vRngOut, kernels/stages/stage_lanes.h): the same operations, so
// each lane gives the scalar bits.
#define MCL_DEFINE_PCG4D(name, T, Out)                               \
  MCL_INLINE Out name(T x, T y, T z, T w) {                          \
    x = x * 1664525u + 1013904223u;                                  \
    y = y * 1664525u + 1013904223u;                                  \
    z = z * 1664525u + 1013904223u;                                  \
    w = w * 1664525u + 1013904223u;                                  \
    x += y * w; y += z * x; z += x * y; w += y * z;                  \
    x ^= x >> 16; y ^= y >> 16; z ^= z >> 16; w ^= w >> 16;          \
    x += y * w; y += z * x; z += x * y; w += y * z;                  \
    Out r;                                                           \
    r.x = x; r.y = y; r.z = z; r.w = w;                              \
    return r;                                                        \
  }
MCL_DEFINE_PCG4D(pcg4d, uint, RngOut)

// Top 24 bits to a float in [0, 1): exact, never 1.0f. For any T, with its conversion to float F.
#define MCL_DEFINE_U32_TO_UNIT(name, T, F, cvt) \
  MCL_INLINE F name(T u) { return cvt(u >> 8) * (1.0f / 16777216.0f); }
#define MCL_CVT_FLOAT(x) ((float)(x))
MCL_DEFINE_U32_TO_UNIT(u32_to_unit, uint, float, MCL_CVT_FLOAT)
// The four numbers of r so (F4 float4 or the lanes' vfloat4; `unit` the matching u32_to_unit).
#define MCL_DEFINE_UNIT4(name, F4, Out, unit) \
  MCL_INLINE F4 name(Out r) {                 \
    F4 u;                                     \
    u.x = unit(r.x);                          \
    u.y = unit(r.y);                          \
    u.z = unit(r.z);                          \
    u.w = unit(r.w);                          \
    return u;                                 \
  }
MCL_DEFINE_UNIT4(unit4, float4, RngOut, u32_to_unit)

// A bijection of 32 bits that spreads every input bit over all output bits (Wellons' "lowbias32"
// constants). pcg4d alone mixes differences in an input's high bits poorly: its first round only
// carries them upwards, so groups 0 and 0x80000000 (camera jitter and the first path bounce) gave
// numbers with correlation 0.26 overall and 0.6 within one pixel, which biased edge pixels of
// path-traced images. The group goes through this mix first (distinct groups stay distinct).
// Written once for any unsigned 32-bit type T (uint here; the packet stages' vuint lanes,
// kernels/stages/stage_lanes.h): the same operations, so each lane gives the scalar bits.
#define MCL_DEFINE_MIX32(name, T) \
  MCL_INLINE T name(T x) {        \
    x ^= x >> 16;                 \
    x *= 0x7feb352du;             \
    x ^= x >> 15;                 \
    x *= 0x846ca68bu;             \
    x ^= x >> 16;                 \
    return x;                     \
  }
MCL_DEFINE_MIX32(mcl_mix32, uint)

// x mixed with the bits of v's three floats in turn (x, y, z), each through mcl_mix32: a hash of a
// point or direction's exact bits.
MCL_INLINE uint mcl_mix_float3(uint x, float3 v) {
  x = mcl_mix32(x ^ as_uint(v.x));
  x = mcl_mix32(x ^ as_uint(v.y));
  return mcl_mix32(x ^ as_uint(v.z));
}

// Four uniform numbers in [0, 1) for dimension group `group` of the given sample; for T uint or
// the lanes' vuint, F4 float4 or vfloat4 (with that type's pcg4d and unit4).
#define MCL_DEFINE_RNG_UNIFORM4(name, T, F4, Out, pcg, unit4)            \
  MCL_INLINE F4 name(uint seed, T pixel, T sample, uint group) {          \
    return unit4(pcg(pixel, sample, (T)(mcl_mix32(group)), (T)(seed)));   \
  }
MCL_DEFINE_RNG_UNIFORM4(rng_uniform4, uint, float4, RngOut, pcg4d, unit4)
