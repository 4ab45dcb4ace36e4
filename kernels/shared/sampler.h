// sampler.h: the one function every stage draws its uniform numbers from: four numbers in [0, 1)
// for dimension group `group` (shared/rng.h) of a pixel's sample, from the frame's sampler
// (FrameParams::sampler). Reads the frame only; a pure function of (seed, pixel, sample, group).
#pragma once
#include "sobol.h"
#include "types.h"

// With Sobol, the first light sample at the camera hit (direct lighting's MCL_DIM_LIGHT, the path
// tracer's bounce-0 light sample MCL_DIM_PATH + 1) takes its point on the light (y, z) from
// dimensions 2 and 3 of the camera's set, whose dimensions 0 and 1 are the pixel jitter: pixel
// position and light point are then stratified jointly in 4D, which is where direct lighting gains
// most. Its light choice (x) and w come from its own set. Every other group is its own set, so
// adding a use never shifts another's numbers.
MCL_INLINE uint sampler_coupled_to_camera(uint group) {
  return group == MCL_DIM_LIGHT || group == MCL_DIM_PATH + 1u;
}

// Sub-sequences: sample s belongs to sub-sequence k = s % splits and is point s / splits of it;
// each sub-sequence has its own scramble seeds (the seed offset by k), so the K sub-means of a
// pixel are independent and their spread estimates the error of the pixel's mean (the film's
// split accumulators, kernels/stages/accumulate.h). splits = 1 is the one sequence per pixel. A
// mask and a shift when K is a power of two (the default 4): a division per lane does not
// vectorise, and both give the same integers. Each function here is written once for T uint
// (F4 float4) and the packet stages' vuint lanes (vfloat4, kernels/stages/stage_lanes.h).
#define MCL_DEFINE_SOBOL_UNIFORM4(name, T, F4, Out, bits, unit4)             \
  MCL_INLINE F4 name(uint seed, uint splits, T pixel, T sample, uint group) { \
    T sub;                                                                   \
    if ((splits & (splits - 1u)) == 0u) {                                    \
      uint shift = 0u;                                                       \
      while ((1u << shift) < splits) ++shift;                                \
      sub = sample & (splits - 1u);                                          \
      sample = sample >> shift;                                              \
    } else {                                                                 \
      sub = sample % splits;                                                 \
      sample = sample / splits;                                              \
    }                                                                        \
    T seeds = seed + sub * 0x9e3779b9u;                                      \
    Out p = bits(seeds, pixel, sample, group);                               \
    if (sampler_coupled_to_camera(group)) {                                  \
      Out c = bits(seeds, pixel, sample, MCL_DIM_CAMERA);                    \
      p.w = p.y;                                                             \
      p.y = c.z;                                                             \
      p.z = c.w;                                                             \
    }                                                                        \
    return unit4(p);                                                         \
  }
MCL_DEFINE_SOBOL_UNIFORM4(sobol_uniform4, uint, float4, RngOut, sobol_owen4_bits, unit4)

#define MCL_DEFINE_SAMPLE_UNIFORM4(name, T, F4, sobol, rng)                                       \
  MCL_INLINE F4 name(MCL_CONSTANT const FrameParams* f, T pixel, T sample, uint group) {          \
    if (f->sampler == MCL_SAMPLER_SOBOL) return sobol(f->seed, f->sobolSplits, pixel, sample, group); \
    return rng(f->seed, pixel, sample, group);                                                    \
  }
MCL_DEFINE_SAMPLE_UNIFORM4(sample_uniform4, uint, float4, sobol_uniform4, rng_uniform4)
