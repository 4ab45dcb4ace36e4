// image_read.h: image input, one entry for every reader: PNG through libpng (image/png_read.h),
// JPEG through libjpeg-turbo (image/jpeg_read.h), OpenEXR through OpenEXR (image/exr_read.h),
// Radiance HDR through stb_image (image/hdr_read.h), every other format (TIFF, TGA, ...) through
// the OpenImageIO module, which is loaded only when such a file is read (image/oiio_loader.h). The
// image's signature picks the reader (a PNG named .jpg is still a PNG), else its name's extension.
#pragma once
#include <string>
#include <vector>

#include "image/oiio_loader.h"

namespace montecl {

struct LayeredImage;

// Reads every channel of the image file path. Throws InputError "<path>: cannot read image:
// <reason>" (one line; the reason check gave when it refused the declared size).
LayeredImage readImageFile(const std::string& path, const ImageSizeCheck& check = {});

// The same for an encoded image held in memory (inside a .glb, a data URI); errors call it name.
LayeredImage readImageMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                             const ImageSizeCheck& check = {});

// The width and height an image declares, from its header alone (no pixel is decoded; of a PNG or
// JPEG file only the first 256 KiB are read when they hold the header). {0, 0} when it cannot be
// read. bytes: the encoded image when it is held in memory (name then only names it), else null.
struct ImageSize {
  int width = 0, height = 0;
};
ImageSize readImageSize(const std::string& name, const std::vector<unsigned char>* bytes = nullptr);

// Whether montecl reads the image file path without OpenImageIO: a PNG, JPEG, EXR or HDR (by its
// signature, else its extension; a CMYK JPEG and an EXR of unsigned integers still go through it).
bool readsWithoutOiio(const std::string& path);

}  // namespace montecl
