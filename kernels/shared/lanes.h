// lanes.h: "varying" lane types for packet stages: one work item runs MCL_LANES (W) consecutive
// wave items, each in one lane of a vector. W is a build define (host/cl/device_tuning.cpp: 16 on
// AVX-512 CPUs, 8 on other CPUs, 1 on GPUs; `--lanes W`), 1 when not defined (the host backend and
// every program built without it). At W = 1 a lane type is the scalar type, and this file compiles
// as C++ through compat.h as well; W = 4, 8, 16 are OpenCL vector types (floatW, uintW, intW).
//
// Bit-identity: every lane performs the scalar program's IEEE operations in the same order (the
// kernels are built with FP_CONTRACT OFF, compat.h), so a packet stage gives the bits of the scalar
// stage body for any W. The packet code must therefore spell out each float3 operation in the
// order compat.h's dot/cross/normalize and GLM use: dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
//
// Masks (vmask): what a comparison gives: 0/1 (int) at W = 1, -1/0 (intW) for vectors. Use only
// v_any, v_all, v_not, `&`, `|` and vsel on them, never their numeric value (v_mask01 converts).
#pragma once
#include "compat.h"

#ifndef MCL_LANES
#define MCL_LANES 1
#endif

#define MCL_LANES_CAT_(a, b) a##b
#define MCL_LANES_CAT(a, b) MCL_LANES_CAT_(a, b)

#if MCL_LANES == 1
typedef float vfloat;
typedef uint vuint;
typedef int vint;
typedef int vmask;
typedef ulong vulong;
#define v_any(m) ((m) != 0)
#define v_all(m) ((m) != 0)
// vsel(m, t, f): t where m is set, f elsewhere (componentwise for vectors).
#define vsel(m, t, f) ((m) ? (t) : (f))
#define v_lane_index() 0u
#define v_f(x) ((float)(x))
#define v_u(x) ((uint)(x))
#define v_as_float(x) as_float(x)
#define v_as_uint(x) as_uint(x)
#define v_as_int(x) ((int)(x))
#define v_int_as_uint(x) ((uint)(x))
#define v_cvt_f_u(x) ((float)(x))
#define v_cvt_f_i(x) ((float)(x))
#define v_cvt_f_ul(x) ((float)(x))
#define v_cvt_i_f(x) ((int)(x))
#define v_cvt_u_f(x) ((uint)(x))
#define v_cvt_u_f_sat(x) ((uint)(x))
#define v_cvt_ul_u(x) ((ulong)(x))
#define v_cvt_u_ul(x) ((uint)(x))
#define v_mask01(m) ((uint)((m) != 0))
#else
#ifndef MCL_OPENCL
#error "MCL_LANES > 1 needs OpenCL vector types"
#endif
#if MCL_LANES != 4 && MCL_LANES != 8 && MCL_LANES != 16
#error "MCL_LANES must be 1, 4, 8 or 16"
#endif
typedef MCL_LANES_CAT(float, MCL_LANES) vfloat;
typedef MCL_LANES_CAT(uint, MCL_LANES) vuint;
typedef MCL_LANES_CAT(int, MCL_LANES) vint;
typedef MCL_LANES_CAT(int, MCL_LANES) vmask;
typedef MCL_LANES_CAT(ulong, MCL_LANES) vulong;
// Any/all lanes set. clang's reductions (a mask register test, e.g. one kortestw on AVX-512) where
// the compiler has them: PoCL 3.1's any()/all() are calls into its library that test lane by lane
// with branches (bench/journal/lanes.md, "Mask tests"). Same result: both test each lane's sign bit.
#if defined(__has_builtin)
#if __has_builtin(__builtin_reduce_or) && __has_builtin(__builtin_reduce_and) && \
    __has_builtin(__builtin_reduce_min) && __has_builtin(__builtin_reduce_add)
#define MCL_HAS_REDUCE 1
#endif
#endif
#ifdef MCL_HAS_REDUCE
#define v_any(m) (__builtin_reduce_or(m) < 0)
#define v_all(m) (__builtin_reduce_and(m) < 0)
#else
#define v_any(m) any(m)
#define v_all(m) all(m)
#endif
#define vsel(m, t, f) select((f), (t), (m))
#define v_f(x) ((vfloat)(x))
#define v_u(x) ((vuint)(x))
#define v_as_float(x) MCL_LANES_CAT(as_float, MCL_LANES)(x)
#define v_as_uint(x) MCL_LANES_CAT(as_uint, MCL_LANES)(x)
#define v_as_int(x) MCL_LANES_CAT(as_int, MCL_LANES)(x)
#define v_int_as_uint(x) MCL_LANES_CAT(as_uint, MCL_LANES)(x)
// Conversions with C's rounding: integer -> float to nearest, float -> integer toward zero.
#define v_cvt_f_u(x) MCL_LANES_CAT(convert_float, MCL_LANES)(x)
#define v_cvt_f_i(x) MCL_LANES_CAT(convert_float, MCL_LANES)(x)
#define v_cvt_f_ul(x) MCL_LANES_CAT(convert_float, MCL_LANES)(x)
#define v_cvt_i_f(x) MCL_LANES_CAT(convert_int, MCL_LANES)(x)
#define v_cvt_u_f(x) MCL_LANES_CAT(convert_uint, MCL_LANES)(x)
#define v_cvt_u_f_sat(x) MCL_LANES_CAT(MCL_LANES_CAT(convert_uint, MCL_LANES), _sat)(x)
#define v_cvt_ul_u(x) MCL_LANES_CAT(convert_ulong, MCL_LANES)(x)
#define v_cvt_u_ul(x) MCL_LANES_CAT(convert_uint, MCL_LANES)(x)
#define v_mask01(m) MCL_LANES_CAT(as_uint, MCL_LANES)(-(m))
#if MCL_LANES == 4
#define v_lane_index() ((uint4)(0u, 1u, 2u, 3u))
#elif MCL_LANES == 8
#define v_lane_index() ((uint8)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u))
#else
#define v_lane_index() ((uint16)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u, 14u, 15u))
#endif
#endif

// Lane 0's value.
#if MCL_LANES == 1
#define v_first_lane(v) (v)
#else
#define v_first_lane(v) ((v).s0)
#endif

// Set lanes where m is clear (works on both mask conventions).
#define v_not(m) ((m) == (vmask)0)

// Vector memory access. PoCL 3.1's vload16/vstore16 (and vloadN on private arrays) compile to
// 8-byte pieces (vmovsd) and stack round trips, so on clang-based compilers the lanes read and
// write through pointers to vector types of 4-byte alignment (clang's aligned attribute on a
// typedef lowers the alignment: unaligned vector loads, vmovups); MCL_LANES_BUILTIN_VLOAD, or
// another compiler, takes the builtins. mcl_ld16/mcl_st16: 16 floats at p + 16 i (any float
// alignment); mcl_ld4/mcl_st4: one float4 at a 16-byte aligned p (a record of types.h).
#if MCL_LANES > 1
#if defined(__clang__) && !defined(MCL_LANES_BUILTIN_VLOAD)
typedef float mcl_float16_u __attribute__((ext_vector_type(16), aligned(4)));
typedef uint mcl_vuint_u __attribute__((ext_vector_type(MCL_LANES), aligned(4)));
#define mcl_ld16(p, i) (*(MCL_GLOBAL const mcl_float16_u*)((p) + 16 * (i)))
#define mcl_st16(v, p, i) (*(MCL_GLOBAL mcl_float16_u*)((p) + 16 * (i)) = (v))
#define mcl_ldu(p) (*(MCL_GLOBAL const mcl_vuint_u*)(p))
#define mcl_ld4(p) (*(MCL_GLOBAL const float4*)(p))
#define mcl_st4(v, p) (*(MCL_GLOBAL float4*)(p) = (v))
#else
#define mcl_ld16(p, i) vload16((i), (p))
#define mcl_st16(v, p, i) vstore16((v), (i), (p))
#define mcl_ldu(p) MCL_LANES_CAT(vload, MCL_LANES)(0, (p))
#define mcl_ld4(p) vload4(0, (p))
#define mcl_st4(v, p) vstore4((v), 0, (p))
#endif
#endif

// Lane values through private arrays, declared `T name[MCL_LANES] MCL_LANE_ALIGN` (aligned for a
// whole vector): v_store_lanes(v, arr) writes lane k to arr[k]; v_loadf_lanes / v_loadu_lanes
// read arr[0 .. W) back as vfloat / vuint. Per-lane code (gathers, scatters, scalar fallbacks)
// loops over k.
#if MCL_LANES == 1
#define MCL_LANE_ALIGN
#define v_store_lanes(v, arr) ((arr)[0] = (v))
#define v_loadf_lanes(arr) ((arr)[0])
#define v_loadu_lanes(arr) ((arr)[0])
#else
#define MCL_LANE_ALIGN __attribute__((aligned(64)))
#define v_store_lanes(v, arr) (*(__typeof__(v)*)(arr) = (v))
#define v_loadf_lanes(arr) (*(vfloat*)(arr))
#define v_loadu_lanes(arr) (*(vuint*)(arr))
#endif
// A vfloat3's rows into three such arrays.
#define v3_store_lanes(v, ax, ay, az) \
  (v_store_lanes((v).x, ax), v_store_lanes((v).y, ay), v_store_lanes((v).z, az))
// The vfloat3 whose lanes are ax[k], ay[k], az[k] (arrays as for v_store_lanes).
#define v3_load_lanes(ax, ay, az) v3_make(v_loadf_lanes(ax), v_loadf_lanes(ay), v_loadf_lanes(az))

// Three lanes of floats: a float3 per lane, structure of arrays.
typedef struct {
  vfloat x, y, z;
} vfloat3;

MCL_INLINE vfloat3 v3_make(vfloat x, vfloat y, vfloat z) {
  vfloat3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
MCL_INLINE vfloat3 v3_splat(float3 v) { return v3_make(v_f(v.x), v_f(v.y), v_f(v.z)); }
MCL_INLINE vfloat3 v3_add(vfloat3 a, vfloat3 b) { return v3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
MCL_INLINE vfloat3 v3_sub(vfloat3 a, vfloat3 b) { return v3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
MCL_INLINE vfloat3 v3_mul(vfloat3 a, vfloat3 b) { return v3_make(a.x * b.x, a.y * b.y, a.z * b.z); }
MCL_INLINE vfloat3 v3_scale(vfloat3 a, vfloat s) { return v3_make(a.x * s, a.y * s, a.z * s); }
MCL_INLINE vfloat3 v3_neg(vfloat3 a) { return v3_make(-a.x, -a.y, -a.z); }
// compat.h's dot: t = a * b; t.x + t.y + t.z (left to right).
MCL_INLINE vfloat v3_dot(vfloat3 a, vfloat3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
MCL_INLINE vfloat3 v3_cross(vfloat3 a, vfloat3 b) {
  return v3_make(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
}
MCL_INLINE vfloat3 v3_normalize(vfloat3 v) { return v3_scale(v, 1.0f / sqrt(v3_dot(v, v))); }
MCL_INLINE vfloat3 v3_select(vmask m, vfloat3 t, vfloat3 f) {
  return v3_make(vsel(m, t.x, f.x), vsel(m, t.y, f.y), vsel(m, t.z, f.z));
}
// The same operations on float3 under the same names with the prefix f3: a function written once
// over a 3-vector prefix V (f3 for float3, v3 for the lanes' vfloat3) instantiates for both.
MCL_INLINE float3 f3_make(float x, float y, float z) { return make_float3(x, y, z); }
MCL_INLINE float3 f3_splat(float3 v) { return v; }
MCL_INLINE float3 f3_add(float3 a, float3 b) { return a + b; }
MCL_INLINE float3 f3_sub(float3 a, float3 b) { return a - b; }
MCL_INLINE float3 f3_scale(float3 a, float s) { return a * s; }
MCL_INLINE float f3_dot(float3 a, float3 b) { return dot(a, b); }
MCL_INLINE float3 f3_neg(float3 a) { return -a; }
MCL_INLINE float3 f3_select(int m, float3 t, float3 f) { return m ? t : f; }
MCL_INLINE float3 f3_mul(float3 a, float3 b) { return a * b; }
MCL_INLINE float3 f3_cross(float3 a, float3 b) { return cross(a, b); }
MCL_INLINE float3 f3_normalize(float3 v) { return normalize(v); }

// --- loads and stores of W consecutive records -------------------------------------------------
// v_load4(p, x, y, z, w): the float4s p[0 .. W) (p: floats, 4 per record, consecutive records),
// transposed into four lane vectors; v_store4 the reverse. Whole vectors (16-float loads, shuffles).
// v_load4_stride / v_store4_stride: the same for records of `stride` floats (the float4 at the
// start of each, 16-byte aligned), one float4 load/store per lane. v_gather4(p, idx, stride): the float4 at
// p + idx[k] * stride for each lane k; v_scatter4 stores there.
#if MCL_LANES == 1
MCL_INLINE void v_load4(MCL_GLOBAL const float* p, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  *x = p[0];
  *y = p[1];
  *z = p[2];
  *w = p[3];
}
MCL_INLINE void v_store4(MCL_GLOBAL float* p, vfloat x, vfloat y, vfloat z, vfloat w) {
  p[0] = x;
  p[1] = y;
  p[2] = z;
  p[3] = w;
}
MCL_INLINE void v_load4_stride(MCL_GLOBAL const float* p, uint stride, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  (void)stride;
  v_load4(p, x, y, z, w);
}
MCL_INLINE void v_store4_stride(MCL_GLOBAL float* p, uint stride, vfloat x, vfloat y, vfloat z, vfloat w) {
  (void)stride;
  v_store4(p, x, y, z, w);
}
MCL_INLINE void v_gather4(MCL_GLOBAL const float* p, vuint idx, uint stride, vfloat* x, vfloat* y, vfloat* z,
                          vfloat* w) {
  v_load4(p + (ulong)idx * stride, x, y, z, w);
}
#define v_gather4_few v_gather4
MCL_INLINE void v_scatter4(MCL_GLOBAL float* p, vuint idx, uint stride, vfloat x, vfloat y, vfloat z, vfloat w) {
  v_store4(p + (ulong)idx * stride, x, y, z, w);
}
#else
// Four float4 records from one float16 (lanes of a 4-lane chunk).
#define MCL_T4_X(v) (v).s048c
#define MCL_T4_Y(v) (v).s159d
#define MCL_T4_Z(v) (v).s26ae
#define MCL_T4_W(v) (v).s37bf
MCL_INLINE float16 mcl_interleave4(float4 x, float4 y, float4 z, float4 w) {
  return (float16)(x.s0, y.s0, z.s0, w.s0, x.s1, y.s1, z.s1, w.s1, x.s2, y.s2, z.s2, w.s2, x.s3, y.s3, z.s3,
                   w.s3);
}
// Lanes 4c .. 4c + 3 of the records at p + o[4c .. 4c + 3] (float offsets, 16-byte aligned): four
// float4 loads into one float16 for MCL_T4_*; the reverse for stores. Whole-register moves and
// shuffles: writing lanes one float at a time into a private array and reading it back as a vector
// costs a store per float and a stalled reload.
#define MCL_LD4X4(p, o0, o1, o2, o3) \
  ((float16)(mcl_ld4((p) + (o0)), mcl_ld4((p) + (o1)), mcl_ld4((p) + (o2)), mcl_ld4((p) + (o3))))
#define MCL_ST4X4(v, p, o0, o1, o2, o3)                                                       \
  (mcl_st4((v).lo.lo, (p) + (o0)), mcl_st4((v).lo.hi, (p) + (o1)), mcl_st4((v).hi.lo, (p) + (o2)), \
   mcl_st4((v).hi.hi, (p) + (o3)))
// The records at p + o[k] (float offsets, one per lane) transposed into four lane vectors, and back.
MCL_INLINE void v_load4_at(MCL_GLOBAL const float* p, const ulong* o, vfloat* x, vfloat* y, vfloat* z,
                           vfloat* w) {
#if MCL_LANES == 4
  float16 a = MCL_LD4X4(p, o[0], o[1], o[2], o[3]);
  *x = MCL_T4_X(a);
  *y = MCL_T4_Y(a);
  *z = MCL_T4_Z(a);
  *w = MCL_T4_W(a);
#elif MCL_LANES == 8
  float16 a = MCL_LD4X4(p, o[0], o[1], o[2], o[3]), b = MCL_LD4X4(p, o[4], o[5], o[6], o[7]);
  *x = (float8)(MCL_T4_X(a), MCL_T4_X(b));
  *y = (float8)(MCL_T4_Y(a), MCL_T4_Y(b));
  *z = (float8)(MCL_T4_Z(a), MCL_T4_Z(b));
  *w = (float8)(MCL_T4_W(a), MCL_T4_W(b));
#else
  float16 a = MCL_LD4X4(p, o[0], o[1], o[2], o[3]), b = MCL_LD4X4(p, o[4], o[5], o[6], o[7]);
  float16 c = MCL_LD4X4(p, o[8], o[9], o[10], o[11]), d = MCL_LD4X4(p, o[12], o[13], o[14], o[15]);
  *x = (float16)(MCL_T4_X(a), MCL_T4_X(b), MCL_T4_X(c), MCL_T4_X(d));
  *y = (float16)(MCL_T4_Y(a), MCL_T4_Y(b), MCL_T4_Y(c), MCL_T4_Y(d));
  *z = (float16)(MCL_T4_Z(a), MCL_T4_Z(b), MCL_T4_Z(c), MCL_T4_Z(d));
  *w = (float16)(MCL_T4_W(a), MCL_T4_W(b), MCL_T4_W(c), MCL_T4_W(d));
#endif
}
MCL_INLINE void v_store4_at(MCL_GLOBAL float* p, const ulong* o, vfloat x, vfloat y, vfloat z, vfloat w) {
#if MCL_LANES == 4
  float16 a = mcl_interleave4(x, y, z, w);
  MCL_ST4X4(a, p, o[0], o[1], o[2], o[3]);
#elif MCL_LANES == 8
  float16 a = mcl_interleave4(x.lo, y.lo, z.lo, w.lo), b = mcl_interleave4(x.hi, y.hi, z.hi, w.hi);
  MCL_ST4X4(a, p, o[0], o[1], o[2], o[3]);
  MCL_ST4X4(b, p, o[4], o[5], o[6], o[7]);
#else
  float16 a = mcl_interleave4(x.lo.lo, y.lo.lo, z.lo.lo, w.lo.lo);
  float16 b = mcl_interleave4(x.lo.hi, y.lo.hi, z.lo.hi, w.lo.hi);
  float16 c = mcl_interleave4(x.hi.lo, y.hi.lo, z.hi.lo, w.hi.lo);
  float16 d = mcl_interleave4(x.hi.hi, y.hi.hi, z.hi.hi, w.hi.hi);
  MCL_ST4X4(a, p, o[0], o[1], o[2], o[3]);
  MCL_ST4X4(b, p, o[4], o[5], o[6], o[7]);
  MCL_ST4X4(c, p, o[8], o[9], o[10], o[11]);
  MCL_ST4X4(d, p, o[12], o[13], o[14], o[15]);
#endif
}
// Float offsets k * stride, and idx[k] * stride.
#define MCL_STRIDE_OFFSETS(o, stride) \
  ulong o[MCL_LANES];                 \
  for (uint k_ = 0; k_ < MCL_LANES; ++k_) o[k_] = (ulong)k_ * (stride)
#define MCL_INDEX_OFFSETS(o, idx, stride)                                      \
  ulong o[MCL_LANES];                                                          \
  {                                                                            \
    uint ai_[MCL_LANES] MCL_LANE_ALIGN;                                        \
    v_store_lanes((idx), ai_);                                                 \
    for (uint k_ = 0; k_ < MCL_LANES; ++k_) o[k_] = (ulong)ai_[k_] * (stride); \
  }
#if MCL_LANES == 4
MCL_INLINE void v_load4(MCL_GLOBAL const float* p, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  float16 a = mcl_ld16(p, 0);
  *x = MCL_T4_X(a);
  *y = MCL_T4_Y(a);
  *z = MCL_T4_Z(a);
  *w = MCL_T4_W(a);
}
MCL_INLINE void v_store4(MCL_GLOBAL float* p, vfloat x, vfloat y, vfloat z, vfloat w) {
  mcl_st16(mcl_interleave4(x, y, z, w), p, 0);
}
#elif MCL_LANES == 8
MCL_INLINE void v_load4(MCL_GLOBAL const float* p, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  float16 a = mcl_ld16(p, 0), b = mcl_ld16(p, 1);
  *x = (float8)(MCL_T4_X(a), MCL_T4_X(b));
  *y = (float8)(MCL_T4_Y(a), MCL_T4_Y(b));
  *z = (float8)(MCL_T4_Z(a), MCL_T4_Z(b));
  *w = (float8)(MCL_T4_W(a), MCL_T4_W(b));
}
MCL_INLINE void v_store4(MCL_GLOBAL float* p, vfloat x, vfloat y, vfloat z, vfloat w) {
  mcl_st16(mcl_interleave4(x.lo, y.lo, z.lo, w.lo), p, 0);
  mcl_st16(mcl_interleave4(x.hi, y.hi, z.hi, w.hi), p, 1);
}
#else
MCL_INLINE void v_load4(MCL_GLOBAL const float* p, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  float16 a = mcl_ld16(p, 0), b = mcl_ld16(p, 1), c = mcl_ld16(p, 2), d = mcl_ld16(p, 3);
  *x = (float16)(MCL_T4_X(a), MCL_T4_X(b), MCL_T4_X(c), MCL_T4_X(d));
  *y = (float16)(MCL_T4_Y(a), MCL_T4_Y(b), MCL_T4_Y(c), MCL_T4_Y(d));
  *z = (float16)(MCL_T4_Z(a), MCL_T4_Z(b), MCL_T4_Z(c), MCL_T4_Z(d));
  *w = (float16)(MCL_T4_W(a), MCL_T4_W(b), MCL_T4_W(c), MCL_T4_W(d));
}
MCL_INLINE void v_store4(MCL_GLOBAL float* p, vfloat x, vfloat y, vfloat z, vfloat w) {
  mcl_st16(mcl_interleave4(x.lo.lo, y.lo.lo, z.lo.lo, w.lo.lo), p, 0);
  mcl_st16(mcl_interleave4(x.lo.hi, y.lo.hi, z.lo.hi, w.lo.hi), p, 1);
  mcl_st16(mcl_interleave4(x.hi.lo, y.hi.lo, z.hi.lo, w.hi.lo), p, 2);
  mcl_st16(mcl_interleave4(x.hi.hi, y.hi.hi, z.hi.hi, w.hi.hi), p, 3);
}
#endif
MCL_INLINE void v_load4_stride(MCL_GLOBAL const float* p, uint stride, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  MCL_STRIDE_OFFSETS(o, stride);
  v_load4_at(p, o, x, y, z, w);
}
MCL_INLINE void v_store4_stride(MCL_GLOBAL float* p, uint stride, vfloat x, vfloat y, vfloat z, vfloat w) {
  MCL_STRIDE_OFFSETS(o, stride);
  v_store4_at(p, o, x, y, z, w);
}
MCL_INLINE void v_gather4(MCL_GLOBAL const float* p, vuint idx, uint stride, vfloat* x, vfloat* y, vfloat* z,
                          vfloat* w) {
  const uint i0 = idx.s0;
  if (v_all(idx == i0)) {  // one record for the whole packet (e.g. one triangle under 16 pixels)
    float4 r = mcl_ld4(p + (ulong)i0 * stride);
    *x = (vfloat)(r.x);
    *y = (vfloat)(r.y);
    *z = (vfloat)(r.z);
    *w = (vfloat)(r.w);
    return;
  }
  MCL_INDEX_OFFSETS(o, idx, stride);
  v_load4_at(p, o, x, y, z, w);
}
// The smallest lane value.
MCL_INLINE uint v_min_lane(vuint v) {
#ifdef MCL_HAS_REDUCE
  return __builtin_reduce_min(v);
#else
#if MCL_LANES == 16
  uint4 b = min(min(v.lo.lo, v.lo.hi), min(v.hi.lo, v.hi.hi));
#elif MCL_LANES == 8
  uint4 b = min(v.lo, v.hi);
#else
  uint4 b = v;
#endif
  uint2 c = min(b.lo, b.hi);
  return min(c.x, c.y);
#endif
}
// v_gather4 for indices with few distinct values (emitters: a light has few triangles): one load
// per distinct index, selected into the lanes that have it.
MCL_INLINE void v_gather4_few(MCL_GLOBAL const float* p, vuint idx, uint stride, vfloat* x, vfloat* y, vfloat* z,
                              vfloat* w) {
  vmask todo = (vmask)(-1);  // every lane
  vfloat rx = v_f(0.0f), ry = v_f(0.0f), rz = v_f(0.0f), rw = v_f(0.0f);
  for (;;) {
    const uint i0 = v_min_lane(vsel(todo, idx, v_u(0xffffffffu)));
    vmask m = todo & (idx == i0);
    float4 r = mcl_ld4(p + (ulong)i0 * stride);
    rx = vsel(m, v_f(r.x), rx);
    ry = vsel(m, v_f(r.y), ry);
    rz = vsel(m, v_f(r.z), rz);
    rw = vsel(m, v_f(r.w), rw);
    todo = todo & v_not(m);
    if (!v_any(todo)) break;
  }
  *x = rx;
  *y = ry;
  *z = rz;
  *w = rw;
}
MCL_INLINE void v_scatter4(MCL_GLOBAL float* p, vuint idx, uint stride, vfloat x, vfloat y, vfloat z, vfloat w) {
  MCL_INDEX_OFFSETS(o, idx, stride);
  v_store4_at(p, o, x, y, z, w);
}
#endif

// The same for a packet of which only the first n lanes have records (n >= 1; the last packet of a
// launch): v_load4_stride_n gives lane k record min(k, n - 1) (every read in bounds; the lanes
// past n repeat the last record, and the caller masks them), v_store4_stride_n writes lanes k < n.
// At W = 1, and for whole packets, v_load4_stride and v_store4_stride.
MCL_INLINE void v_load4_stride_n(MCL_GLOBAL const float* p, uint stride, uint n, vfloat* x, vfloat* y, vfloat* z,
                                 vfloat* w) {
#if MCL_LANES > 1
  if (n < MCL_LANES) {
    v_gather4(p, min(v_lane_index(), v_u(n - 1u)), stride, x, y, z, w);
    return;
  }
#endif
  (void)n;
  v_load4_stride(p, stride, x, y, z, w);
}
MCL_INLINE void v_store4_stride_n(MCL_GLOBAL float* p, uint stride, uint n, vfloat x, vfloat y, vfloat z, vfloat w) {
#if MCL_LANES > 1
  if (n < MCL_LANES) {
    float ax[MCL_LANES] MCL_LANE_ALIGN, ay[MCL_LANES] MCL_LANE_ALIGN, az[MCL_LANES] MCL_LANE_ALIGN,
        aw[MCL_LANES] MCL_LANE_ALIGN;
    v_store_lanes(x, ax);
    v_store_lanes(y, ay);
    v_store_lanes(z, az);
    v_store_lanes(w, aw);
    for (uint k = 0; k < n; ++k) mcl_st4(((float4)(ax[k], ay[k], az[k], aw[k])), p + k * stride);
    return;
  }
#endif
  (void)n;
  v_store4_stride(p, stride, x, y, z, w);
}

// v_load4 and v_store4 (consecutive float4 records) for a packet of n lanes, as above.
MCL_INLINE void v_load4_n(MCL_GLOBAL const float* p, uint n, vfloat* x, vfloat* y, vfloat* z, vfloat* w) {
  if (n < MCL_LANES) v_load4_stride_n(p, 4u, n, x, y, z, w);
  else v_load4(p, x, y, z, w);
}
MCL_INLINE void v_store4_n(MCL_GLOBAL float* p, uint n, vfloat x, vfloat y, vfloat z, vfloat w) {
  if (n < MCL_LANES) v_store4_stride_n(p, 4u, n, x, y, z, w);
  else v_store4(p, x, y, z, w);
}
// v_scatter4 of the first n lanes only (n >= 1).
MCL_INLINE void v_scatter4_n(MCL_GLOBAL float* p, vuint idx, uint stride, uint n, vfloat x, vfloat y, vfloat z,
                             vfloat w) {
#if MCL_LANES > 1
  if (n < MCL_LANES) {
    uint ai[MCL_LANES] MCL_LANE_ALIGN;
    float ax[MCL_LANES] MCL_LANE_ALIGN, ay[MCL_LANES] MCL_LANE_ALIGN, az[MCL_LANES] MCL_LANE_ALIGN,
        aw[MCL_LANES] MCL_LANE_ALIGN;
    v_store_lanes(idx, ai);
    v_store_lanes(x, ax);
    v_store_lanes(y, ay);
    v_store_lanes(z, az);
    v_store_lanes(w, aw);
    for (uint k = 0; k < n; ++k) mcl_st4(((float4)(ax[k], ay[k], az[k], aw[k])), p + (ulong)ai[k] * stride);
    return;
  }
#endif
  (void)n;
  v_scatter4(p, idx, stride, x, y, z, w);
}
// The lanes of a packet from item `first` of `count` that have an item (at least one).
MCL_INLINE uint v_packet_lanes(uint first, uint count) { return count - first < MCL_LANES ? count - first : MCL_LANES; }

// Records of two float4s (a, b) at p[0 .. 2W) as float4s: the a parts into ax.., the b parts into
// bx.. (whole vector loads, then even / odd lanes).
MCL_INLINE void v_load4_pairs(MCL_GLOBAL const float* p, vfloat* ax, vfloat* ay, vfloat* az, vfloat* aw, vfloat* bx,
                              vfloat* by, vfloat* bz, vfloat* bw) {
#if MCL_LANES == 1
  v_load4(p, ax, ay, az, aw);
  v_load4(p + 4, bx, by, bz, bw);
#else
  vfloat x0, y0, z0, w0, x1, y1, z1, w1;
  v_load4(p, &x0, &y0, &z0, &w0);
  v_load4(p + 4 * MCL_LANES, &x1, &y1, &z1, &w1);
  *ax = (vfloat)(x0.even, x1.even);
  *ay = (vfloat)(y0.even, y1.even);
  *az = (vfloat)(z0.even, z1.even);
  *aw = (vfloat)(w0.even, w1.even);
  *bx = (vfloat)(x0.odd, x1.odd);
  *by = (vfloat)(y0.odd, y1.odd);
  *bz = (vfloat)(z0.odd, z1.odd);
  *bw = (vfloat)(w0.odd, w1.odd);
#endif
}

// uint lanes from W consecutive uints, or gathered by index.
#if MCL_LANES == 1
#define v_load_uints(p) ((p)[0])
MCL_INLINE vuint v_gather_uint(MCL_GLOBAL const uint* p, vuint idx) { return p[idx]; }
#else
#define v_load_uints(p) mcl_ldu(p)
MCL_INLINE vuint v_gather_uint(MCL_GLOBAL const uint* p, vuint idx) {
  uint ai[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(idx, ai);
  for (uint k = 0; k < MCL_LANES; ++k) ai[k] = p[ai[k]];
  return v_loadu_lanes(ai);
}
#endif

// One float at p + i * stride: v_gather_float's float form, for the functions written once for
// floats and lanes (their table reads, G##gather_float).
MCL_INLINE float mcl_gather_float(MCL_GLOBAL const float* p, uint i, uint stride) { return p[(ulong)i * stride]; }
// Four floats at p + i * stride (v_gather4's float form; also under v_gather4_few's name).
MCL_INLINE void mcl_gather4(MCL_GLOBAL const float* p, uint i, uint stride, float* x, float* y, float* z, float* w) {
  MCL_GLOBAL const float* q = p + (ulong)i * stride;
  *x = q[0], *y = q[1], *z = q[2], *w = q[3];
}
#define mcl_gather4_few mcl_gather4

// One float per lane at p + idx[k] * stride.
#if MCL_LANES == 1
MCL_INLINE vfloat v_gather_float(MCL_GLOBAL const float* p, vuint idx, uint stride) { return p[(ulong)idx * stride]; }
#else
MCL_INLINE vfloat v_gather_float(MCL_GLOBAL const float* p, vuint idx, uint stride) {
  uint ai[MCL_LANES] MCL_LANE_ALIGN;
  float af[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(idx, ai);
  for (uint k = 0; k < MCL_LANES; ++k) af[k] = p[(ulong)ai[k] * stride];
  return v_loadf_lanes(af);
}
#endif

// Lanes set in m (at most W).
MCL_INLINE uint v_count(vmask m) {
#if MCL_LANES == 1
  return m != 0 ? 1u : 0u;
#elif defined(MCL_HAS_REDUCE)
  return __builtin_reduce_add(v_mask01(m));
#else
  uint b[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(v_mask01(m), b);
  uint n = 0;
  for (uint k = 0; k < MCL_LANES; ++k) n += b[k];
  return n;
#endif
}

// n / d and n % d per lane, exact, for a uniform d > 0: a float estimate of the quotient, then
// integer corrections until every lane's remainder lies in [0, d) (one step in practice; the
// estimate is off by at most a few units for any n below 2^32). The scalar program's `/` and `%`.
MCL_INLINE void v_divmod(vuint n, uint d, vuint* q, vuint* r) {
#if MCL_LANES == 1
  *q = n / d;
  *r = n % d;
#else
  vuint qq = v_cvt_u_f_sat(v_cvt_f_u(n) * (1.0f / (float)d));
  vint rr = v_as_int(n - qq * d);  // n - q d as a signed number (|error| * d < 2^31)
  for (;;) {
    vmask lo = rr < 0, hi = rr >= (int)d;
    if (!v_any(lo | hi)) break;
    qq = vsel(lo, qq - 1u, vsel(hi, qq + 1u, qq));
    rr = vsel(lo, rr + (int)d, vsel(hi, rr - (int)d, rr));
  }
  *q = qq;
  *r = v_int_as_uint(rr);
#endif
}
