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

// A file of fileBytes cannot hold more than maxRatio decoded bytes per byte (its compression's
// best case): a header declaring more describes pixels the file does not have, and decoding would
// allocate them all before finding out (a 9.8 KB EXR cost 7.2 GB and 17-47 s). "" when it can.
inline std::string fileSizeProblem(unsigned long long decodedBytes, unsigned long long fileBytes,
                                   unsigned long long maxRatio, const std::string& compression) {
  if (fileBytes == 0 || decodedBytes / fileBytes < maxRatio) return "";
  return "declares " + std::to_string(decodedBytes) + " bytes of pixels in a file of " + std::to_string(fileBytes) +
         " bytes, more than " + compression + " compression reaches (" + std::to_string(maxRatio) +
         ":1): the file is truncated or its header is wrong";
}

}  // namespace montecl
