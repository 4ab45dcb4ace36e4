// png_write.cpp: linear float RGB -> sRGB 8-bit -> PNG file, with libpng's simplified API.
#include "image/png_write.h"

#include <png.h>

#include <cmath>

#include "util/errors.h"

namespace montecl {

std::uint8_t linearToSrgb8(float x) {
  if (!(x > 0.0f)) return 0;  // negatives and NaN
  if (x >= 1.0f) return 255;
  float s = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(s * 255.0f));
}

void writePngSrgb(const std::string& path, const std::string& displayPath, int width, int height,
                  const std::vector<float>& rgb) {
  std::vector<std::uint8_t> bytes(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) bytes[i] = linearToSrgb8(rgb[i]);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGB;  // 8-bit, non-linear: libpng tags it sRGB
  if (!png_image_write_to_file(&image, path.c_str(), 0, bytes.data(), 0, nullptr)) {
    std::string why = image.message[0] ? image.message : "libpng failed";
    png_image_free(&image);
    throw RuntimeError("cannot write " + displayPath + ": " + why);
  }
}

}  // namespace montecl
