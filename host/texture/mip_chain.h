// mip_chain.h: a texture's linear RGBA image and its mip pyramid. Reads a decoded LayeredImage
// (image/exr_layers.h); writes float RGBA levels, rows bottom to top (row 0 holds v in [0, 1/h)).
// Integer images (8/16-bit) are sRGB-decoded to linear before any filtering; float images are
// taken as linear. Alpha is never decoded.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace montecl {

struct LayeredImage;

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;  // width * height, row 0 = the image's bottom row
  const glm::vec4& at(int x, int y) const { return texels[std::size_t(y) * width + x]; }
};

// The sRGB transfer function's inverse (IEC 61966-2-1): 8-bit 128 -> 0.2158605.
float srgbToLinear(float encoded);

// True when image's pixels are integers (uint8, uint16, ...): sRGB-encoded colour.
bool isIntegerImage(const LayeredImage& image);

// RGBA from 1 (grey), 2 (grey, alpha), 3 (RGB) or 4+ (RGBA) channels, rows flipped to bottom-first,
// colour sRGB-decoded when srgb. hasAlpha tells whether the file had an alpha channel.
RgbaImage rgbaFromImage(const LayeredImage& image, bool srgb, bool* hasAlpha = nullptr);

// The next coarser level: max(1, floor(w / 2)) x max(1, floor(h / 2)), each texel the exact
// area average (box filter) of the source texels its footprint covers; a 2x2 box for even sizes,
// fractional weights for odd ones, so the mean of every level equals the mean of level 0.
RgbaImage downsample(const RgbaImage& image);

// Level 0 (image itself) down to 1 x 1.
std::vector<RgbaImage> buildMipChain(RgbaImage image);

// Number of levels of a w x h pyramid: 1 + floor(log2(max(w, h))).
int mipLevelCount(int width, int height);

}  // namespace montecl
