// film.h: per-pixel statistics read back from the device: the exact state the accumulate kernel
// keeps (kernels/stages/accumulate.h): the running mean and M2 (rgb: sum of squared deviations
// from the mean, Welford) each as a float-float pair hi + lo, and the 64-bit sample count; and
// the AOV sums. mean[p] (the hi part) is the mean correctly rounded to float. Row 0 at the top.
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "kernels/shared/types.h"  // MCL_AOV_VECTORS

namespace montecl {

// The squared standard error of a mean over K independent sub-sequences with counts n_k and
// means m_k (the mean m = sum n_k m_k / n): sum_k (n_k / n)^2 K'/(K'-1) (m_k - m)^2 over the K'
// sub-sequences with samples, which for equal counts is sum_k (m_k - m)^2 / (K (K-1)): unbiased
// for equal counts whatever the correlation of the samples within a sub-sequence. Infinite with
// fewer than two sub-sequences holding samples.
inline double splitMeanVariance(const double* n, const double* m, std::size_t k) {
  double total = 0.0, mean = 0.0, sum = 0.0;
  std::size_t filled = 0;
  for (std::size_t i = 0; i < k; ++i)
    if (n[i] > 0.0) total += n[i], mean += n[i] * m[i], ++filled;
  if (filled < 2) return INFINITY;
  mean /= total;
  for (std::size_t i = 0; i < k; ++i) {
    if (!(n[i] > 0.0)) continue;
    const double w = n[i] / total, d = m[i] - mean;
    sum += w * w * d * d;
  }
  return sum * double(filled) / double(filled - 1);
}

struct Film {
  int width = 0, height = 0;
  std::vector<glm::vec4> mean, meanLo;  // rgb: mean of the sample values = mean + meanLo; w: 0
  std::vector<glm::vec4> m2, m2Lo;      // rgb: sum over samples of (x - mean)^2 = m2 + m2Lo; w: 0
  std::vector<std::uint64_t> count;     // samples per pixel
  // With AOVs: MCL_AOV_VECTORS (3) per pixel, sums over samples of (albedo, depth), (normal, 0) and
  // (emission seen directly, 0) (kernels/stages/record_aov.h); else empty.
  std::vector<glm::vec4> aovSum;
  // With the sobol sampler's K > 1 sub-sequences: K per pixel, split[K p + k] = sub-sequence k's
  // mean (rgb) and its sample count (w, uint bits); else empty.
  std::vector<glm::vec4> split;
  // Adaptive sampling under a budget (render.adaptive): the count each pixel's current round
  // brings it to (render/adaptive_budget.h), so a checkpoint resumes mid-round exactly; else empty.
  std::vector<std::uint64_t> roundTarget;
  // Whether a pixel's samples are correlated (the sobol sampler): var/n is then not the error of
  // its mean, with or without sub-sequences (set by the renderer; statistics code asks it).
  bool correlated = false;

  // Sub-sequences per pixel (0 without split accumulators).
  std::size_t splits() const { return count.empty() ? 0 : split.size() / count.size(); }
  std::uint32_t splitCount(std::size_t p, std::size_t k) const {
    std::uint32_t c;
    std::memcpy(&c, &split[splits() * p + k].w, 4);
    return c;
  }

  std::size_t pixelCount() const { return count.size(); }
  // Mean of channel c in double (hi + lo).
  double meanOf(std::size_t p, int c) const { return double(mean[p][c]) + double(meanLo[p][c]); }
  // M2 of channel c in double (hi + lo).
  double m2Of(std::size_t p, int c) const { return double(m2[p][c]) + double(m2Lo[p][c]); }
  // Unbiased variance of one sample of channel c (0 below two samples). Rounding can leave M2 a
  // hair below 0 (clamped); a NaN or infinite M2 (an overflowed sample) stays NaN or infinite.
  double variance(std::size_t p, int c) const {
    const double n = double(count[p]);
    if (!(n > 1.0)) return 0.0;
    const double v = m2Of(p, c) / (n - 1.0);
    return v < 0.0 ? 0.0 : v;
  }

  // The squared standard error of the pixel's mean of channel c: with sub-sequences, from the
  // spread of their K independent means (splitMeanVariance); without them variance / n, which
  // assumes independent samples.
  double meanVariance(std::size_t p, int c) const {
    const std::size_t k = splits();
    const double n = double(count[p]);
    if (k == 0) return n > 1.0 ? variance(p, c) / n : 0.0;
    double ns[64], ms[64];
    for (std::size_t i = 0; i < k && i < 64; ++i) ns[i] = double(splitCount(p, i)), ms[i] = double(split[k * p + i][c]);
    return splitMeanVariance(ns, ms, std::min<std::size_t>(k, 64));
  }

  // Mean radiance per pixel, interleaved RGB (0 where a pixel has no samples).
  std::vector<float> meanRgb() const {
    std::vector<float> rgb(mean.size() * 3, 0.0f);
    for (std::size_t p = 0; p < mean.size(); ++p)
      for (int c = 0; c < 3; ++c) rgb[3 * p + c] = count[p] > 0 ? mean[p][c] : 0.0f;
    return rgb;
  }

  // Splits device film words into this film's fields: mean.w / meanLo.w carry the count's low and
  // high 32 bits (as float bit patterns), which become count[] while the w lanes are zeroed.
  // The inverse of unpackCounts: the device film words of mean and meanLo, count bits in w.
  void packCounts(std::vector<glm::vec4>& meanWords, std::vector<glm::vec4>& meanLoWords) const {
    meanWords = mean;
    meanLoWords = meanLo;
    for (std::size_t p = 0; p < mean.size(); ++p) {
      const std::uint32_t lo = std::uint32_t(count[p]), hi = std::uint32_t(count[p] >> 32);
      std::memcpy(&meanWords[p].w, &lo, 4);
      std::memcpy(&meanLoWords[p].w, &hi, 4);
    }
  }

  void unpackCounts() {
    count.resize(mean.size());
    for (std::size_t p = 0; p < mean.size(); ++p) {
      std::uint32_t lo, hi;
      std::memcpy(&lo, &mean[p].w, 4);
      std::memcpy(&hi, &meanLo[p].w, 4);
      count[p] = std::uint64_t(lo) | (std::uint64_t(hi) << 32);
      mean[p].w = meanLo[p].w = 0.0f;
    }
  }
};

}  // namespace montecl
