// jpeg_read.h: JPEG input through libjpeg-turbo, the pixels OpenImageIO's JPEG reader gives (the
// library's default decode: 8-bit grey or RGB, code / 255 as floats), without loading OpenImageIO.
// Reads only the bytes it is given.
#pragma once
#include <cstddef>
#include <string>

#include "image/oiio_loader.h"

namespace montecl {

struct LayeredImage;

// Decodes the JPEG of data[0 .. size) into out (channels Y or R G B, pixelType uint8). Returns ""
// on success, else the one-line reason (a corrupt or truncated file, a size imageSizeProblem or
// check refuses); out is then empty. unsupported is set (and "" returned, out empty) for a CMYK or
// YCCK JPEG, which OpenImageIO converts itself. Never throws for a bad file, never prints.
std::string decodeJpeg(const unsigned char* data, std::size_t size, LayeredImage& out, const ImageSizeCheck& check,
                       bool& unsupported);

}  // namespace montecl
