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

// x snapped to the grid quantum x {1, 1.5, 2, 3, 4, 6, 8, 12, ...} (powers of two and their 1.5x),
// the nearest level by ratio (frexp and constants only: exact on every machine); 0 below half a
// quantum. A round's targets then take few distinct values, and the wave loop runs one group per
// count (sample_schedule.h): at exact shares, 330 groups for a 128x128 path render at 256 spp.
std::uint64_t snapToGrid(double x, std::uint64_t quantum) {
  const double u = x / double(quantum);
  if (!(u >= 0.5)) return 0;
  if (!(u < 9.0e15)) return std::uint64_t(9.0e15) * quantum;
  int e = 0;
  const double m = std::frexp(u, &e);  // u = m 2^e, m in [0.5, 1)
  const double below = std::ldexp(1.0, e - 1);
  // Boundaries at the geometric means: sqrt(1.5) / 2 between 2^(e-1) and 1.5 2^(e-1), sqrt(3) / 2
  // between that and 2^e.
  const double level = m < 0.6123724356957945 ? below : m < 0.8660254037844386 ? 1.5 * below : 2.0 * below;
  return std::uint64_t(level) * quantum;
}

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
  // A pixel's target at a given lambda: lambda w snapped to the grid, at least its count, at most
  // the cap. Nondecreasing in lambda, so is the round's sum.
  const auto targetAt = [&](double lambda, std::size_t i) {
    const std::uint64_t c = counts[mine[i]];
    return std::min(std::max(snapToGrid(lambda * weight[i], quantum), c), std::max(c, b.maxSpp));
  };
  const auto adds = [&](double lambda) {
    std::uint64_t s = 0;
    for (std::size_t i = 0; i < mine.size(); ++i) s += targetAt(lambda, i) - counts[mine[i]];
    return s;
  };
  // The largest lambda whose targets add at most the round's samples: bisection, a fixed number
  // of steps, the same on every machine.
  double lo = 0.0, hi = 1.0;
  while (adds(hi) <= size) hi *= 2.0;
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    (adds(mid) <= size ? lo : hi) = mid;
  }
  for (std::size_t i = 0; i < mine.size(); ++i) {
    target[mine[i]] = targetAt(lo, i);
    added += target[mine[i]] - counts[mine[i]];
  }
  // The rest (below one grid step of some pixel) a quantum each to the pixels farthest below
  // lambda w, so the round adds exactly its samples.
  std::vector<std::size_t> order(mine.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto deficit = [&](std::size_t i) { return hi * weight[i] - double(target[mine[i]]); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) { return deficit(a) > deficit(c); });
  for (bool progress = true; added < size && progress;) {
    progress = false;
    for (std::size_t i : order) {
      std::uint64_t& t = target[mine[i]];
      const std::uint64_t e = std::min({quantum, size - added, b.maxSpp > t ? b.maxSpp - t : 0});
      t += e, added += e, progress |= e > 0;
      if (added == size) break;
    }
  }
  return added;
}

}  // namespace montecl
