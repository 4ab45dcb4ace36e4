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
// split accumulators, kernels/stages/accumulate.h). splits = 1 is the one sequence per pixel.
MCL_INLINE uint sobol_split_seed(uint seed, uint splits, uint sample) { return seed + (sample % splits) * 0x9e3779b9u; }

MCL_INLINE float4 sobol_uniform4(uint seed, uint splits, uint pixel, uint sample, uint group) {
  seed = sobol_split_seed(seed, splits, sample);
  sample /= splits;
  RngOut p = sobol_owen4_bits(seed, pixel, sample, group);
  if (sampler_coupled_to_camera(group)) {
    RngOut c = sobol_owen4_bits(seed, pixel, sample, MCL_DIM_CAMERA);
    p.w = p.y;
    p.y = c.z;
    p.z = c.w;
  }
  return make_float4(u32_to_unit(p.x), u32_to_unit(p.y), u32_to_unit(p.z), u32_to_unit(p.w));
}

MCL_INLINE float4 sample_uniform4(MCL_CONSTANT const FrameParams* f, uint pixel, uint sample, uint group) {
  if (f->sampler == MCL_SAMPLER_SOBOL) return sobol_uniform4(f->seed, f->sobolSplits, pixel, sample, group);
  return rng_uniform4(f->seed, pixel, sample, group);
}
