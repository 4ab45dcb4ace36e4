// hdr_read.h: Radiance RGBE (.hdr) input through stb_image (Debian's libstb-dev), the floats
// OpenImageIO's HDR reader gives (mantissa times 2^(exponent - 136), exact in float), without
// loading OpenImageIO. Reads the file, or only the bytes it is given.
#pragma once
#include <cstddef>
#include <string>

#include "image/oiio_loader.h"

namespace montecl {

struct LayeredImage;

// Whether data[0 .. size) starts as a Radiance file does ("#?RADIANCE\n" or "#?RGBE\n").
bool isHdrSignature(const unsigned char* data, std::size_t size);

// Decodes the Radiance file path, or the encoded bytes data[0 .. size) when data is not null, into
// out (channels R G B, pixelType "float"). Returns "" on success, else the one-line reason (a
// corrupt or truncated file, a size imageSizeProblem or check refuses: then no pixel is decoded);
// out is then empty. Never throws for a bad file, never prints.
std::string decodeHdr(const std::string& path, const unsigned char* data, std::size_t size, LayeredImage& out,
                      const ImageSizeCheck& check);

}  // namespace montecl
