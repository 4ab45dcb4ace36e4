// exr_writer.h: writes montecl's float planes as an OpenEXR file with OpenEXR itself (Debian's
// libopenexr-dev, ~3 MiB of libraries), not through the OpenImageIO module: loading that module
// maps ~260 shared libraries and added ~120 MiB to a render's peak resident memory just to write
// its image (Sponza 960x540: 166 MiB to a .pfm, 302 MiB to an .exr).
#pragma once
#include <string>

namespace montecl {
struct LayeredImage;

// Every plane as a 32-bit float channel, ZIP-compressed, and every image.attributes entry as a
// string header attribute, to path (displayPath names it in errors). Throws RuntimeError.
void writeExrFile(const std::string& path, const std::string& displayPath, const LayeredImage& image);
}  // namespace montecl
