// mip_chain.cpp: sRGB decoding and the box-filtered mip pyramid of a texture (see mip_chain.h).
#include "texture/mip_chain.h"

#include <algorithm>
#include <cmath>

#include "image/exr_layers.h"

namespace montecl {

float srgbToLinear(float c) {
  if (c <= 0.04045f) return c / 12.92f;
  return float(std::pow((double(c) + 0.055) / 1.055, 2.4));
}

bool isIntegerImage(const LayeredImage& image) {
  const std::string& t = image.pixelType;
  return t.rfind("uint", 0) == 0 || t.rfind("int", 0) == 0;
}

namespace {

// srgbToLinear of every code of an n-bit integer image (n = 8 or 16), computed once.
const std::vector<float>& srgbTable(int bits) {
  static const std::vector<float> t8 = [] {
    std::vector<float> t(256);
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  static const std::vector<float> t16 = [] {
    std::vector<float> t(65536);
    for (int i = 0; i < 65536; ++i) t[i] = srgbToLinear(float(i) / 65535.0f);
    return t;
  }();
  return bits == 8 ? t8 : t16;
}

}  // namespace

RgbaImage rgbaFromImage(const LayeredImage& image, bool srgb, bool* hasAlpha) {
  // Integer codes decode through a table (the value OpenImageIO gives is code / max).
  const std::string& type = image.pixelType;
  const int bits = type == "uint8" || type == "int8" ? 8 : type == "uint16" || type == "int16" ? 16 : 0;
  const std::vector<float>* table = srgb && bits ? &srgbTable(bits) : nullptr;
  const float maxCode = bits == 8 ? 255.0f : 65535.0f;
  RgbaImage out;
  out.width = image.width;
  out.height = image.height;
  out.texels.assign(image.pixelCount(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const std::size_t nch = image.planes.size();
  const bool grey = nch < 3;
  const bool alpha = nch == 2 || nch >= 4;
  if (hasAlpha) *hasAlpha = alpha;
  const std::vector<float>* a = alpha ? &image.planes[nch == 2 ? 1 : 3] : nullptr;
  for (int y = 0; y < image.height; ++y) {
    const std::size_t src = std::size_t(image.height - 1 - y) * image.width;  // flip: row 0 at the bottom
    for (int x = 0; x < image.width; ++x) {
      glm::vec4& t = out.texels[std::size_t(y) * image.width + x];
      for (int c = 0; c < 3; ++c) {
        float v = nch == 0 ? 0.0f : image.planes[grey ? 0 : c][src + x];
        if (!std::isfinite(v)) v = 0.0f;
        if (table) t[c] = (*table)[std::size_t(std::clamp(v, 0.0f, 1.0f) * maxCode + 0.5f)];  // the code
        else t[c] = srgb ? srgbToLinear(std::clamp(v, 0.0f, 1.0f)) : v;
      }
      if (a) t.w = std::isfinite((*a)[src + x]) ? (*a)[src + x] : 0.0f;
    }
  }
  return out;
}

namespace {

// Weights of the source texels covering destination texel d along one axis: the interval
// [d * n / m, (d + 1) * n / m) of the n source texels, split at texel boundaries.
struct Tap {
  int index;
  float weight;
};

std::vector<std::vector<Tap>> boxTaps(int n, int m) {
  std::vector<std::vector<Tap>> taps(m);
  for (int d = 0; d < m; ++d) {
    const double lo = double(d) * n / m, hi = double(d + 1) * n / m;
    for (int s = int(std::floor(lo)); s < hi && s < n; ++s) {
      const double cover = std::min(hi, double(s + 1)) - std::max(lo, double(s));
      if (cover > 0.0) taps[d].push_back({s, float(cover * m / n)});
    }
  }
  return taps;
}

}  // namespace

RgbaImage downsample(const RgbaImage& in) {
  RgbaImage out;
  out.width = std::max(1, in.width / 2);
  out.height = std::max(1, in.height / 2);
  const auto tx = boxTaps(in.width, out.width), ty = boxTaps(in.height, out.height);
  // Horizontal pass into rows of the source height, then vertical.
  std::vector<glm::vec4> rows(std::size_t(out.width) * in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      glm::vec4 s(0.0f);
      for (const Tap& t : tx[x]) s += in.at(t.index, y) * t.weight;
      rows[std::size_t(y) * out.width + x] = s;
    }
  out.texels.resize(std::size_t(out.width) * out.height);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      glm::vec4 s(0.0f);
      for (const Tap& t : ty[y]) s += rows[std::size_t(t.index) * out.width + x] * t.weight;
      out.texels[std::size_t(y) * out.width + x] = s;
    }
  return out;
}

int mipLevelCount(int width, int height) {
  int levels = 1;
  for (int s = std::max(width, height); s > 1; s /= 2) ++levels;
  return levels;
}

std::vector<RgbaImage> buildMipChain(RgbaImage image) {
  std::vector<RgbaImage> levels;
  const int count = mipLevelCount(image.width, image.height);
  levels.reserve(count);
  levels.push_back(std::move(image));
  while (int(levels.size()) < count) levels.push_back(downsample(levels.back()));
  return levels;
}

}  // namespace montecl
