// path_waves.h: the bounce loop of one path-tracing wave (--integrator path), run by the wave loop
// (render/wavefront.cpp) between generate and accumulate.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "render/stage_runner.h"

namespace montecl {

struct PathWaveCounts {
  std::uint64_t bounceRays = 0;   // continuation rays traced (camera rays not included)
  std::uint64_t shadowRays = 0;   // next-event occlusion queries traced
  std::vector<std::uint64_t> survivors;  // [b]: live paths shaded at bounce b (0: camera rays)
};

// Runs the bounces of a wave of n camera rays already generated: per bounce intersect ->
// shade_path -> (record_aov at bounce 0 when aovs) -> intersect_shadow -> path_gather, on the live
// paths only, until none is left; adds to counts.
// "paths per bounce: 0: 16384, 1: 16384 (100%), 2: 12000 (73.2%), ..." (for -v).
std::string survivorsSummary(const std::vector<std::uint64_t>& survivors);

// fused: each bounce is one launch of wave_path (kernels/stages/wave_fused.h), bounce 0 generating the
// camera rays itself (the caller then launches no generate).
void runPathWave(StageRunner& run, std::uint32_t n, std::uint32_t lightSamples, bool aovs, bool fused,
                 PathWaveCounts& counts);

}  // namespace montecl
