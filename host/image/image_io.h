// image_io.h: writing RGB images, chosen by extension: .exr (32-bit float, OpenEXR),
// .png (8-bit sRGB, clamped, libpng), .pfm (32-bit float, by hand). Always atomic.
#pragma once
#include <string>
#include <vector>

namespace montecl {

// Throws InputError ("<path>: unsupported image format '.xyz' (use .png, .exr or .pfm)") when the
// extension is not supported or the folder does not exist; call before rendering.
void checkOutputPath(const std::string& path);

// Writes width x height interleaved RGB (row 0 at the top) to path atomically.
void writeRgbImage(const std::string& path, int width, int height, const std::vector<float>& rgb);

}  // namespace montecl
