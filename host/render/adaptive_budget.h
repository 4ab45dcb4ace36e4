// adaptive_budget.h: the rounds of adaptive sampling under a budget (render.adaptive, --adaptive):
// the count each pixel reaches next. A pure function of the film as it stands, the pixels owned
// and the budget (never of time or of the device), so a render stopped by --time, resumed from a
// checkpoint or repeated elsewhere follows the same schedule. Reads the film; writes the targets.
#pragma once
#include <cstdint>
#include <vector>

#include "image/film.h"

namespace montecl {

struct AdaptiveBudget {
  std::uint64_t firstPass = 16;  // samples every pixel gets before any allocation (min(--min-spp, spp))
  std::uint64_t maxSpp = 1024;   // most samples one pixel gets (--max-spp)
  std::uint64_t total = 0;       // the budget: samples over the pixels owned (spp x pixels)
  std::uint64_t quantum = 1;     // a round adds multiples of this per pixel (the K sub-sequences)
};

// Pixel p's weight: the square root of its estimated per-sample relative variance,
// n x sum_c errVar_c / (mean_c^2 + 0.01) / 3 (errVar: the squared error of the mean from the
// film's estimate, mean_c: the channel's mean; relMSE's denominator), averaged over the 3x3
// pixels around p that have 2 or more samples (the estimate has few degrees of freedom per pixel).
double adaptiveWeight(const Film& film, std::size_t p);

// Starts the next round: sets target[p] (>= counts[p]) for every pixel of `mine`. The first
// round brings every pixel to firstPass. Later rounds add min(total - done, done) samples (the
// total doubles), rounded down to the quantum, split by water-filling: target_p =
// clamp(snap(lambda w_p), count_p, maxSpp) with the largest lambda whose targets add at most the
// round's samples (counts proportional to w minimise the summed relMSE for a given total: Neyman
// allocation); snap: the nearest of quantum x {1, 1.5, 2, 3, 4, 6, ...}, so that a round has few
// distinct counts (the wave loop runs a group per count); the rest a quantum each to the pixels
// farthest below lambda w, so the round adds exactly its samples. Returns them (0: done).
std::uint64_t nextAdaptiveRound(const Film& film, const std::vector<std::uint32_t>& mine,
                                const std::vector<std::uint64_t>& counts, const AdaptiveBudget& budget,
                                std::vector<std::uint64_t>& target);

}  // namespace montecl
