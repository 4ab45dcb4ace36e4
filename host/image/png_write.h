// png_write.h: 8-bit sRGB PNG output through libpng (no OpenImageIO: PNG renders start fast).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace montecl {

// The sRGB transfer function of linear x, clamped to [0, 1] and rounded to 8 bits (NaN -> 0).
std::uint8_t linearToSrgb8(float x);

// Writes width x height interleaved linear RGB (row 0 at the top) as an 8-bit sRGB PNG to exactly
// path (callers make it atomic). Throws RuntimeError "cannot write <displayPath>: <reason>".
void writePngSrgb(const std::string& path, const std::string& displayPath, int width, int height,
                  const std::vector<float>& rgb);

}  // namespace montecl
