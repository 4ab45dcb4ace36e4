// png_read.h: PNG input through libpng, the texels OpenImageIO's PNG reader gives (code / max as
// floats; grey, grey + alpha, palette expanded to RGB, tRNS to alpha, 8 and 16 bits), without
// loading OpenImageIO. Reads only the bytes it is given.
#pragma once
#include <cstddef>
#include <string>

#include "image/oiio_loader.h"

namespace montecl {

struct LayeredImage;

// Decodes the PNG of data[0 .. size) into out (channels Y / Y A / R G B / R G B A, pixelType uint8
// or uint16). Returns "" on success, else the one-line reason (a corrupt or truncated file, a size
// imageSizeProblem or check refuses: then no pixel is decoded); out is then empty. Never throws
// for a bad file, never prints.
std::string decodePng(const unsigned char* data, std::size_t size, LayeredImage& out, const ImageSizeCheck& check);

}  // namespace montecl
