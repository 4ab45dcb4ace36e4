// image_limits.h: the one rule on the size an image file declares, asked by every image reader
// (image/png_read, image/jpeg_read, the OpenImageIO module) before any pixel is decoded.
#pragma once
#include <string>

namespace montecl {

// montecl's renders are at most 16384 x 16384 pixels; pixels are read as an array from (0, 0), so
// a data window elsewhere would shift the image. "" when the declared size is accepted.
inline std::string imageSizeProblem(long width, long height, int channels, long x = 0, long y = 0) {
  constexpr long kMaxSide = 16384;
  constexpr int kMaxChannels = 1024;
  if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide)
    return "image is " + std::to_string(width) + " x " + std::to_string(height) + " pixels (at most " +
           std::to_string(kMaxSide) + " per side)";
  if (x != 0 || y != 0)
    return "data window starts at (" + std::to_string(x) + ", " + std::to_string(y) +
           "), not at (0, 0): crop or re-save the image with its data window at the origin";
  if (channels <= 0 || channels > kMaxChannels) return "image has " + std::to_string(channels) + " channels";
  return "";
}

}  // namespace montecl
