// wave_planner.cpp: sizes the next wave from the measured rate (render/wave_planner.h).
#include "render/wave_planner.h"

#include <algorithm>
#include <cmath>

namespace montecl {

std::uint64_t planWave(const WavePlanner& planner, std::uint64_t cap, std::uint64_t left, double rate,
                       double timeLeft) {
  if (left == 0 || cap == 0 || !(timeLeft > 0.0)) return 0;
  const std::uint64_t limit = std::min(cap, left);
  const double minWave = double(std::max<std::uint64_t>(1, planner.minWave));
  if (!(rate > 0.0) || !std::isfinite(rate)) return std::max<std::uint64_t>(1, std::min(limit, planner.firstWave));
  double items = rate * std::max(planner.waveSeconds, 1e-6);
  if (std::isfinite(timeLeft)) {
    const double fit = rate * timeLeft;  // items the time left holds
    if (fit < 0.5 * std::min(minWave, double(limit))) return 0;
    // Split the time left into whole waves of at most waveSeconds: the last one ends at the limit,
    // and a rate that is off by x% moves the end by x% of one wave at most.
    const double waves = std::max(1.0, std::ceil(timeLeft / std::max(planner.waveSeconds, 1e-6) - 1e-9));
    items = fit / waves;
  }
  items = std::max(items, minWave);
  if (items >= double(limit)) return limit;
  return std::max<std::uint64_t>(1, std::uint64_t(items));
}

}  // namespace montecl
