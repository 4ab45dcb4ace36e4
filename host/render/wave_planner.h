// wave_planner.h: how many pixel samples the next wave gets, from the rate measured on the waves
// so far (a pure function; the wave loop in render/wavefront.cpp calls it before every wave).
// Waves last about WavePlanner::waveSeconds each, so the progress bar moves several times a
// second, and with a time limit they are sized so the last one ends at the limit. The image does
// not depend on the plan: every pixel's samples are accumulated in sample order (kernels/stages/stage_common.h), so any sequence of wave sizes renders the same.
#pragma once
#include <cstdint>

namespace montecl {

struct WavePlanner {
  double waveSeconds = 0.25;       // aimed duration of one wave
  std::uint64_t firstWave = 4096;  // items of the first wave, before any rate is measured
  std::uint64_t minWave = 1024;    // fewest items of a planned wave (launch overhead)
};

// Items of the next wave, at most cap (the allocated wave) and left (items left in this pass), at
// least 1 while anything is left. rate: items per second measured so far (<= 0: none yet).
// timeLeft: seconds to the time limit (infinity: none). Returns 0 to stop: the time limit has
// passed, or what is left of it is less than half of the shortest wave worth launching.
std::uint64_t planWave(const WavePlanner& planner, std::uint64_t cap, std::uint64_t left, double rate,
                       double timeLeft);

}  // namespace montecl
