// film.h: per-pixel statistics read back from the device: the running mean (rgb, w = sample count)
// and M2 (rgb: sum of squared deviations from the mean, Welford) the accumulate kernel keeps, and
// the AOV sums. Row 0 at the top.
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <vector>

namespace montecl {

struct Film {
  int width = 0, height = 0;
  std::vector<glm::vec4> mean;   // rgb: mean of the sample values; w: number of samples n
  std::vector<glm::vec4> m2;     // rgb: sum over samples of (x - mean)^2
  // With AOVs: 2 per pixel, sums over samples of (albedo, depth) and (normal, 0); else empty.
  std::vector<glm::vec4> aovSum;

  // Unbiased variance of one sample of channel c (0 below two samples).
  double variance(size_t p, int c) const {
    const double n = mean[p].w;
    return n > 1.0 ? std::max(0.0, double(m2[p][c]) / (n - 1.0)) : 0.0;
  }

  // Mean radiance per pixel, interleaved RGB (0 where a pixel has no samples).
  std::vector<float> meanRgb() const {
    std::vector<float> rgb(mean.size() * 3, 0.0f);
    for (size_t p = 0; p < mean.size(); ++p)
      for (int c = 0; c < 3; ++c) rgb[3 * p + c] = mean[p].w > 0.0f ? mean[p][c] : 0.0f;
    return rgb;
  }
};

}  // namespace montecl
