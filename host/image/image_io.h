// image_io.h: writing images through OpenImageIO, chosen by extension: .exr (32-bit float,
// linear), .png (8-bit sRGB, clamped), .pfm (32-bit float, linear). Always atomic.
#pragma once
#include <string>
#include <vector>

namespace montecl {

// Throws InputError ("<path>: unsupported image format '.xyz' (use .png, .exr or .pfm)") when the
// extension is not supported or the folder does not exist; call before rendering.
void checkOutputPath(const std::string& path);

// Writes width x height interleaved RGB (row 0 at the top) to path atomically.
void writeRgbImage(const std::string& path, int width, int height, const std::vector<float>& rgb);

// Reads an image as interleaved RGB floats (linear for .exr/.pfm); for tests and merging.
std::vector<float> readRgbImage(const std::string& path, int& width, int& height);

}  // namespace montecl
