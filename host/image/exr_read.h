// exr_read.h: OpenEXR input through OpenEXR itself (the library montecl's EXR output links), the
// planes, channel names and order, pixel type and "montecl:" string attributes OpenImageIO's EXR
// reader gives, without loading OpenImageIO. Reads the file, or only the bytes it is given.
#pragma once
#include <cstddef>
#include <string>

#include "image/oiio_loader.h"

namespace montecl {

struct LayeredImage;

// Whether data[0 .. size) starts with OpenEXR's magic number.
bool isExrSignature(const unsigned char* data, std::size_t size);

// Decodes part 0 (level 0 of a tiled file) of the OpenEXR file path, or of the encoded bytes
// data[0 .. size) when data is not null, into out: every channel as float planes in OpenImageIO's
// order, pixelType "half", "float" or (mixed) "float". Returns "" on success, else the one-line
// reason (a corrupt or truncated file, OpenEXR's exception caught; a size imageSizeProblem or check
// refuses, before any pixel is decoded); out is then empty. unsupported is set (and "" returned,
// out empty) for a file with 32-bit unsigned integer channels or a luminance-chroma image (Y, RY,
// BY), whose conversions to float RGB OpenImageIO does itself. Never throws for a bad file, never prints.
std::string decodeExr(const std::string& path, const unsigned char* data, std::size_t size, LayeredImage& out,
                      const ImageSizeCheck& check, bool& unsupported);

}  // namespace montecl
