// adaptive_budget.cpp: the rounds of adaptive sampling under a budget (adaptive_budget.h).
#include "render/adaptive_budget.h"

#include <algorithm>
#include <cmath>

namespace montecl {
namespace {

// relMSE's denominator offset (mean^2 + 0.01), as scripts/image_metrics.py measures it.
constexpr double kRelOffset = 0.01;
// Every pixel keeps at least this share of the mean weight: an estimate of 0 from a few samples
// (all sub-sequences agreeing by chance) must not starve a pixel for the rest of the render.
constexpr double kWeightFloor = 0.05;

double perSampleRelVariance(const Film& film, std::size_t p) {
  const double n = double(film.count[p]);
  double v = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double m = film.meanOf(p, c);
    v += film.meanVariance(p, c) / (m * m + kRelOffset);
  }
  return n * v / 3.0;
}

}  // namespace

double adaptiveWeight(const Film& film, std::size_t p) {
  const int w = film.width, h = film.height, x = int(p % std::size_t(w)), y = int(p / std::size_t(w));
  double sum = 0.0;
  int used = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
      const std::size_t q = std::size_t(qy) * std::size_t(w) + std::size_t(qx);
      if (film.count[q] < 2) continue;
      const double v = perSampleRelVariance(film, q);
      if (!std::isfinite(v)) continue;  // an overflowed sample: no usable estimate
      sum += v, ++used;
    }
  return used ? std::sqrt(sum / used) : 0.0;
}

std::uint64_t nextAdaptiveRound(const Film& film, const std::vector<std::uint32_t>& mine,
                                const std::vector<std::uint64_t>& counts, const AdaptiveBudget& b,
                                std::vector<std::uint64_t>& target) {
  std::uint64_t done = 0, added = 0;
  bool first = false;
  for (std::uint32_t p : mine) done += counts[p], first |= counts[p] < std::min(b.firstPass, b.maxSpp);
  if (first) {
    for (std::uint32_t p : mine) {
      target[p] = std::max(counts[p], std::min(b.firstPass, b.maxSpp));
      added += target[p] - counts[p];
    }
    return added;
  }
  const std::uint64_t quantum = std::max<std::uint64_t>(1, b.quantum);
  std::uint64_t size = b.total > done ? std::min(b.total - done, done) : 0;
  size -= size % quantum;
  std::uint64_t room = 0;
  for (std::uint32_t p : mine) room += b.maxSpp > counts[p] ? b.maxSpp - counts[p] : 0;
  if (size == 0 || room == 0) return 0;
  if (size >= room) {  // every pixel reaches the cap
    for (std::uint32_t p : mine) target[p] = std::max(counts[p], b.maxSpp);
    return room;
  }
  std::vector<double> weight(mine.size());
  double mean = 0.0;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const double w = adaptiveWeight(film, mine[i]);
    mean += weight[i] = std::isfinite(w) ? w : 0.0;
  }
  mean /= double(mine.size());
  for (double& w : weight) w = mean > 0.0 ? std::max(w, kWeightFloor * mean) : 1.0;
  // The samples the round adds at a given lambda; nondecreasing in lambda.
  const auto share = [&](double lambda, std::size_t i) {
    const double c = double(counts[mine[i]]);
    return std::min(std::max(lambda * weight[i], c), double(b.maxSpp)) - c;
  };
  const auto adds = [&](double lambda) {
    double s = 0.0;
    for (std::size_t i = 0; i < mine.size(); ++i) s += share(lambda, i);
    return s;
  };
  double lo = 0.0, hi = 1.0;
  while (adds(hi) < double(size)) hi *= 2.0;
  for (int i = 0; i < 64; ++i) {  // bisection: a fixed number of steps, the same on every machine
    const double mid = 0.5 * (lo + hi);
    (adds(mid) < double(size) ? lo : hi) = mid;
  }
  // Each share to whole quanta by running sums: the round adds close to its samples in all.
  double running = 0.0;
  std::uint64_t given = 0;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const std::uint32_t p = mine[i];
    running += share(hi, i) / double(quantum);
    const std::uint64_t upTo = std::uint64_t(std::floor(running + 0.5)) * quantum;
    std::uint64_t extra = upTo > given ? upTo - given : 0;
    given += extra;
    target[p] = std::min(counts[p] + extra, std::max(counts[p], b.maxSpp));
    added += target[p] - counts[p];
  }
  return added;
}

}  // namespace montecl
