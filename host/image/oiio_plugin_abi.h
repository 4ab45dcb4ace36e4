// oiio_plugin_abi.h: the C entry points of libmontecl_oiio.so, the module that holds every use of
// OpenImageIO. montecl loads it with dlopen only when an image goes through OpenImageIO (image input
// other than PNG, JPEG, EXR and HDR, image/image_read.h; montecl's EXR output uses OpenEXR directly, image/exr_writer.h: the write entry point
// serves the tests' fixture images in other formats): Debian's OpenImageIO pulls in about 260 shared libraries (OpenCV,
// FFmpeg, ...) whose relocation alone costs ~0.35 s, which a PNG render should not pay.
// Both sides are built from this header by the same compiler in the same build, so the functions
// take montecl's own structs; they never throw: 0 on success, else a one-line message in err.
#pragma once
#include <cstddef>

namespace montecl {
struct LayeredImage;
}

extern "C" {
// Writes every plane of image as a 32-bit float channel (zip-compressed for EXR) to path, whose
// extension picks the format. A channel named "Z" is marked as the depth channel. Every entry of
// image->attributes is written as a string header attribute of that name.
typedef int (*MonteclOiioWriteFn)(const char* path, const montecl::LayeredImage* image, char* err,
                                  std::size_t errSize);
// Asked with the size an opened file declares, before any pixel is decoded: 0 to go on, else a
// one-line reason in err (the read then fails with it). The caller owns the rule (texture budget,
// memory check), so a tiny file declaring 16384 x 16384 pixels costs no memory.
typedef int (*MonteclOiioSizeCheckFn)(void* context, int width, int height, int channels, char* err,
                                      std::size_t errSize);
// Reads every channel of path as float planes, channel names as stored, and every string header
// attribute whose name starts with "montecl:" into image->attributes. check (may be null) is asked
// first with checkContext.
typedef int (*MonteclOiioReadFn)(const char* path, montecl::LayeredImage* image, MonteclOiioSizeCheckFn check,
                                 void* checkContext, char* err, std::size_t errSize);
// The same from an encoded image held in memory (an image inside a .glb or a data URI): name's
// extension picks the reader, as a path's does; the bytes are decoded in place, never through a
// temporary file.
typedef int (*MonteclOiioReadMemoryFn)(const char* name, const unsigned char* data, std::size_t size,
                                       montecl::LayeredImage* image, MonteclOiioSizeCheckFn check,
                                       void* checkContext, char* err, std::size_t errSize);
}

#define MONTECL_OIIO_WRITE_SYMBOL "montecl_oiio_write"
#define MONTECL_OIIO_READ_SYMBOL "montecl_oiio_read"
#define MONTECL_OIIO_READ_MEMORY_SYMBOL "montecl_oiio_read_memory"
