// bump_gradient.cpp: a height map's gradient texture (see bump_gradient.h).
#include "texture/bump_gradient.h"

#include <algorithm>

#include "kernels/shared/types.h"

namespace montecl {
namespace {

// Index i of a row of n texels under wrap mode w, as the kernels' texture_wrap_mode reads it.
int wrapIndex(int i, int n, std::uint32_t w) {
  if (w == MCL_WRAP_CLAMP) return std::clamp(i, 0, n - 1);
  if (w == MCL_WRAP_MIRROR) {
    const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
    return m >= n ? 2 * n - 1 - m : m;
  }
  return ((i % n) + n) % n;
}

float height(const glm::vec4& t) { return (t.x + t.y + t.z) * (1.0f / 3.0f); }

}  // namespace

RgbaImage bumpGradient(const RgbaImage& heights, float scale, std::uint32_t wrapS, std::uint32_t wrapT) {
  const int w = heights.width, h = heights.height;
  RgbaImage out;
  out.width = w;
  out.height = h;
  out.texels.assign(heights.texels.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const float kHalfMax = 65504.0f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // The neighbours' distance in texels: 2, or 1 where a clamped edge repeats the texel itself,
      // or 0 along an axis of one texel (no slope there).
      const int xa = wrapIndex(x - 1, w, wrapS), xb = wrapIndex(x + 1, w, wrapS);
      const int ya = wrapIndex(y - 1, h, wrapT), yb = wrapIndex(y + 1, h, wrapT);
      const int dx = wrapS == MCL_WRAP_CLAMP ? std::min(x + 1, w - 1) - std::max(x - 1, 0) : (w > 1 ? 2 : 0);
      const int dy = wrapT == MCL_WRAP_CLAMP ? std::min(y + 1, h - 1) - std::max(y - 1, 0) : (h > 1 ? 2 : 0);
      // Rows run up the image (v up), so row y + 1 is the neighbour at larger v.
      const float gu = dx > 0 ? (height(heights.at(xb, y)) - height(heights.at(xa, y))) * float(w) / float(dx) : 0.0f;
      const float gv = dy > 0 ? (height(heights.at(x, yb)) - height(heights.at(x, ya))) * float(h) / float(dy) : 0.0f;
      out.texels[std::size_t(y) * w + x] =
          glm::vec4(std::clamp(gu * scale, -kHalfMax, kHalfMax), std::clamp(gv * scale, -kHalfMax, kHalfMax), 0.0f, 1.0f);
    }
  return out;
}

}  // namespace montecl
