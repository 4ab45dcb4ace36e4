// sobol.h: Owen-scrambled Sobol points, a pure function of (seed, pixel, sample index, dimension
// set). Each set is a 4D point: Sobol dimensions 0..3 of the Joe-Kuo direction numbers
// (new-joe-kuo-6.21201; dimension 0 is the van der Corput bit reversal), every dimension
// nested-uniform scrambled with its own seed, and the sample index itself nested-uniform scrambled
// per (seed, pixel, set), so each pixel walks its own randomly placed, aligned block of the
// sequence (Burley 2020, "Practical Hash-based Owen Scrambling"). Sets are decorrelated by hashing
// (seed, pixel, set) into all five scramble seeds. uint arithmetic only: the same bits on every
// device, and each function is written once for uint and the lanes' vuint (stage_lanes.h).
#pragma once
#include "rng.h"

// Bit i to bit 31 - i. Written once for any unsigned 32-bit type T (uint here, the lanes' vuint in
// kernels/stages/stage_lanes.h), as mcl_mix32 is.
#define MCL_DEFINE_REVERSE_BITS(name, T)                                 \
  MCL_INLINE T name(T x) {                                               \
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);             \
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);             \
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);             \
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);             \
    return (x >> 16) | (x << 16);                                        \
  }

// Nested uniform (Owen) scramble of a 32-bit fixed-point value: bit k of the result (counted from
// the most significant) is bit k flipped by a hash of the seed and the bits above it. On the
// bit-reversed value that is a map whose bit k depends only on bits below k: adding a number and
// x ^= x * even carry information upwards only (Burley's Laine-Karras style hash and constants).
#define MCL_DEFINE_OWEN_SCRAMBLE(name, T, reverse) \
  MCL_INLINE T name(T x, T seed) {                 \
    x = reverse(x);                                \
    x += seed;                                     \
    x ^= x * 0x6c50b47cu;                          \
    x ^= x * 0xb82f1e52u;                          \
    x ^= x * 0xc7afe638u;                          \
    x ^= x * 0x8d22f6e6u;                          \
    return reverse(x);                             \
  }
MCL_DEFINE_REVERSE_BITS(mcl_reverse_bits, uint)
MCL_DEFINE_OWEN_SCRAMBLE(mcl_owen_scramble, uint, mcl_reverse_bits)

// Sobol dimensions 1..3 of index i as 32-bit fixed point. The direction numbers v_k (left-aligned,
// k = 1, 2, ...) follow from each primitive polynomial's recurrence, so no table is needed:
// dim 1 (x + 1, m = 1):                 v_k = v_{k-1} ^ (v_{k-1} >> 1)
// dim 2 (x^2 + x + 1, m = 1, 3):        v_k = v_{k-1} ^ v_{k-2} ^ (v_{k-2} >> 2)
// dim 3 (x^3 + x + 1, m = 1, 3, 1):     v_k = v_{k-2} ^ v_{k-3} ^ (v_{k-3} >> 3)
// Every bit of i is visited (an Owen-scrambled index is anywhere in [0, 2^32)). Written once for
// the index type T (uint, or the lanes' vuint: the direction numbers are the same in every lane).
#define MCL_DEFINE_SOBOL4(name, T, Out, reverse)                                \
  MCL_INLINE Out name(T i) {                                                    \
    uint d1 = 0x80000000u;                                                      \
    uint p2 = 0x80000000u, q2 = 0xc0000000u;                                    \
    uint p3 = 0x80000000u, q3 = 0xc0000000u, r3 = 0x20000000u;                  \
    T x1 = (T)(0u), x2 = (T)(0u), x3 = (T)(0u);                                 \
    for (uint k = 0; k < 32u; ++k) {                                            \
      T bit = (T)(0u) - ((i >> k) & 1u); /* all ones where bit k of i is set */ \
      x1 ^= bit & d1;                                                           \
      x2 ^= bit & p2;                                                           \
      x3 ^= bit & p3;                                                           \
      d1 ^= d1 >> 1;                                                            \
      uint n2 = q2 ^ p2 ^ (p2 >> 2);                                            \
      p2 = q2;                                                                  \
      q2 = n2;                                                                  \
      uint n3 = q3 ^ p3 ^ (p3 >> 3);                                            \
      p3 = q3;                                                                  \
      q3 = r3;                                                                  \
      r3 = n3;                                                                  \
    }                                                                           \
    Out r;                                                                      \
    r.x = reverse(i);                                                           \
    r.y = x1;                                                                   \
    r.z = x2;                                                                   \
    r.w = x3;                                                                   \
    return r;                                                                   \
  }
MCL_DEFINE_SOBOL4(mcl_sobol4, uint, RngOut, mcl_reverse_bits)

// The 4D point `sample` of dimension set `set` of this pixel, 32-bit fixed point per dimension:
// the five scramble seeds of (seed, pixel, set) (x for the index, then one per dimension), the
// scrambled index's Sobol point, each dimension scrambled. For T uint or vuint (with its pcg4d,
// sobol4, Owen scramble and mix32).
#define MCL_DEFINE_SOBOL_OWEN4_BITS(name, T, Out, pcg, sobol4, scramble, mix)   \
  MCL_INLINE Out name(T seed, T pixel, T sample, uint set) {                    \
    Out h = pcg(pixel, (T)(mcl_mix32(set)), seed, (T)(0x50b01u));               \
    Out p = sobol4(scramble(sample, h.x));                                      \
    p.x = scramble(p.x, h.y);                                                   \
    p.y = scramble(p.y, h.z);                                                   \
    p.z = scramble(p.z, h.w);                                                   \
    p.w = scramble(p.w, mix(h.x ^ 0x9e3779b9u));                                \
    return p;                                                                   \
  }
MCL_DEFINE_SOBOL_OWEN4_BITS(sobol_owen4_bits, uint, RngOut, pcg4d, mcl_sobol4, mcl_owen_scramble, mcl_mix32)
