// compat.h: lets the shared headers compile both as OpenCL C 1.2 and as C++17.
// In OpenCL it maps nothing; in C++ it maps OpenCL vector types, qualifiers and built-ins onto GLM
// and the standard library, so pure functions (RNG, sampling, intersection) are tested on the host.
#pragma once

#if defined(__OPENCL_C_VERSION__) || defined(__OPENCL_VERSION__)
#define MCL_OPENCL 1
#endif

#ifdef MCL_OPENCL
// No FMA contraction (OpenCL C lets a compiler fuse a * b + c by default; PoCL does): the host
// backend compiles these headers with -ffp-contract=off, so both round every operation the same.
#pragma OPENCL FP_CONTRACT OFF
#define MCL_GLOBAL __global
#define MCL_CONSTANT __constant
#define MCL_INLINE inline
#define MCL_ALWAYS_INLINE inline __attribute__((always_inline))
#define make_float2(a, b) ((float2)((a), (b)))
#define make_float3(a, b, c) ((float3)((a), (b), (c)))
#define make_float4(a, b, c, d) ((float4)((a), (b), (c), (d)))
#define MCL_ATOMIC_INC(p) atomic_inc(p)
#define MCL_STATIC_ASSERT(cond, msg)
#define MCL_ALIGN16
#define MCL_ALIGN32
// A hint to fetch the cache line at p (no effect on results): set where the device build defines
// MCL_PREFETCH_HINTS (host/cl/device_tuning.cpp: CPUs), else nothing.
#ifdef MCL_PREFETCH_HINTS
#define MCL_PREFETCH(p) __builtin_prefetch(p)
#endif
// dot, cross, length and normalize of float3, written out with the same float operations, in
// the same order, as GLM's on the host. OpenCL lets the built-ins use any precision or order
// (Oclgrind, for one, differs from PoCL in the last bit), and a last-bit difference in a cosine
// near grazing becomes a large relative one in a pdf. Only float3 is used in these headers.
MCL_INLINE float mcl_dot3(float3 a, float3 b) {
  float3 t = a * b;
  return t.x + t.y + t.z;
}
MCL_INLINE float3 mcl_cross3(float3 a, float3 b) {
  return (float3)(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
}
MCL_INLINE float mcl_length3(float3 v) { return sqrt(mcl_dot3(v, v)); }
MCL_INLINE float3 mcl_normalize3(float3 v) { return v * (1.0f / sqrt(mcl_dot3(v, v))); }
#undef dot  // some implementations (PoCL) define the built-ins as macros
#undef cross
#undef length
#undef normalize
#define dot(a, b) mcl_dot3(a, b)
#define cross(a, b) mcl_cross3(a, b)
#define length(v) mcl_length3(v)
#define normalize(v) mcl_normalize3(v)
// Four half floats (texels: RGBA half) at p + 4 i, as floats; core OpenCL 1.2 (no cl_khr_fp16).
#define mcl_load_half4(p, i) vload_half4((i), (MCL_GLOBAL const half*)(p))
#define mcl_load_half(p, i) vload_half((i), (MCL_GLOBAL const half*)(p))
#else
#include <glm/glm.hpp>
#include <math.h>  // libstdc++'s math.h puts the float overloads of sqrt, fmin, ... in the global namespace
#include <cstdint>
#include <cstring>
using float2 = glm::vec2;
using float3 = glm::vec3;
using float4 = glm::vec4;
using uint = std::uint32_t;
using ulong = std::uint64_t;
using uint2 = glm::uvec2;
using uint4 = glm::uvec4;
using int2 = glm::ivec2;
#define MCL_GLOBAL
#define MCL_CONSTANT
#define MCL_INLINE inline
#define MCL_ALWAYS_INLINE inline
#define MCL_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
#define MCL_ALIGN16 alignas(16)
#define MCL_ALIGN32 alignas(32)
inline float2 make_float2(float a, float b) { return float2(a, b); }
inline float3 make_float3(float a, float b, float c) { return float3(a, b, c); }
inline float4 make_float4(float a, float b, float c, float d) { return float4(a, b, c, d); }
using glm::cross;
using glm::dot;
using glm::normalize;
using glm::length;
inline float3 fmin(float3 a, float3 b) { return glm::min(a, b); }
inline float3 fmax(float3 a, float3 b) { return glm::max(a, b); }
inline float3 fabs(float3 a) { return glm::abs(a); }
inline float as_float(uint u) { float f; std::memcpy(&f, &u, 4); return f; }
inline uint as_uint(float f) { uint u; std::memcpy(&u, &f, 4); return u; }
inline uint MCL_ATOMIC_INC(volatile uint* p) { return __atomic_fetch_add(p, 1u, __ATOMIC_RELAXED); }
using ushort = std::uint16_t;
// IEEE half -> float, exact (what vload_half does on a device).
inline float mcl_half_to_float(ushort h) {
  uint sign = uint(h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
  if (e == 0) {
    float f = float(m) * (1.0f / 16777216.0f);
    return sign ? -f : f;
  }
  return as_float(sign | (e == 31 ? 0x7f800000u | (m << 13) : ((e + 112u) << 23) | (m << 13)));
}
inline float mcl_load_half(const ushort* p, uint i) { return mcl_half_to_float(p[i]); }
inline float4 mcl_load_half4(const ushort* p, uint i) {
  const ushort* q = p + 4 * std::size_t(i);
  return float4(mcl_half_to_float(q[0]), mcl_half_to_float(q[1]), mcl_half_to_float(q[2]), mcl_half_to_float(q[3]));
}
#endif

// The select and "any lane" of the functions written once for floats and lanes (MCL_DEFINE_*), at
// one lane: the conditional operator and the condition itself.
#define MCL_SEL1(m, t, f) ((m) ? (t) : (f))
#define MCL_ANY1(m) (m)
// Vector helpers that read the same in both languages (no swizzles, which GLM lacks by default).
MCL_INLINE float3 xyz(float4 v) { return make_float3(v.x, v.y, v.z); }
MCL_INLINE float4 with_w(float3 v, float w) { return make_float4(v.x, v.y, v.z, w); }
