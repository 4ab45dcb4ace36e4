// film.h: per-pixel accumulated samples read back from the device: sum (rgb, w = sample count)
// and sum of squares (rgb), row 0 at the top. Turns them into the mean image.
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace montecl {

struct Film {
  int width = 0, height = 0;
  std::vector<glm::vec4> sum;    // rgb: sum of sample values; w: number of samples
  std::vector<glm::vec4> sumSq;  // rgb: sum of squared sample values
  // With AOVs: 2 per pixel, sums over samples of (albedo, depth) and (normal, 0); else empty.
  std::vector<glm::vec4> aovSum;

  // Mean radiance per pixel, interleaved RGB (0 where a pixel has no samples).
  std::vector<float> meanRgb() const {
    std::vector<float> rgb(sum.size() * 3, 0.0f);
    for (size_t p = 0; p < sum.size(); ++p) {
      if (sum[p].w <= 0.0f) continue;
      for (int c = 0; c < 3; ++c) rgb[3 * p + c] = sum[p][c] / sum[p].w;
    }
    return rgb;
  }
};

}  // namespace montecl
