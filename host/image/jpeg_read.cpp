// jpeg_read.cpp: decodes an encoded JPEG held in memory into float planes with libjpeg-turbo
// (jpeg_read.h).
#include "image/jpeg_read.h"

#include <csetjmp>
#include <cstdio>
// jpeglib.h needs size_t and FILE declared before it.
#include <jpeglib.h>
#include <jerror.h>

#include <vector>

#include "image/exr_layers.h"
#include "image/image_limits.h"

namespace montecl {
namespace {

// The library's error manager, extended with where its errors jump back to (never into the
// library again) and the message they leave.
struct JpegErrors {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void jpegFail(j_common_ptr cinfo) {
  JpegErrors* e = reinterpret_cast<JpegErrors*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, e->message);
  std::longjmp(e->jump, 1);
}
// Warnings (corrupt data the library recovers from) are not printed, as OpenImageIO prints none;
// but a file that ends early is an error, not an image padded with grey rows.
void jpegWarning(j_common_ptr cinfo, int level) {
  if (level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF) jpegFail(cinfo);
}

// The two steps of a decode that call into the library, each under its own setjmp and holding no
// C++ object (a longjmp skips no destructor, and clobbers nothing the caller reads): false after
// an error, its message in errors.message.
bool jpegStart(jpeg_decompress_struct& cinfo, JpegErrors& errors, const unsigned char* data, std::size_t size,
               bool& cmyk) {
  if (setjmp(errors.jump)) return false;
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
  if (!cmyk) jpeg_start_decompress(&cinfo);
  return true;
}

bool jpegRows(jpeg_decompress_struct& cinfo, JpegErrors& errors, unsigned char* pixels, std::size_t rowBytes) {
  if (setjmp(errors.jump)) return false;
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = pixels + std::size_t(cinfo.output_scanline) * rowBytes;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  return true;
}

// Owns the decompressor: destroyed whichever way decodeJpeg returns.
struct JpegDecoder {
  jpeg_decompress_struct cinfo{};
  JpegErrors errors{};
  JpegDecoder() {
    cinfo.err = jpeg_std_error(&errors.mgr);
    errors.mgr.error_exit = jpegFail;
    errors.mgr.emit_message = jpegWarning;
    jpeg_create_decompress(&cinfo);
  }
  ~JpegDecoder() { jpeg_destroy_decompress(&cinfo); }
  JpegDecoder(const JpegDecoder&) = delete;
  JpegDecoder& operator=(const JpegDecoder&) = delete;
};

}  // namespace

std::string decodeJpeg(const unsigned char* data, std::size_t size, LayeredImage& out, const ImageSizeCheck& check,
                       bool& unsupported) {
  unsupported = false;
  out = LayeredImage{};
  if (size < 3 || data[0] != 0xff || data[1] != 0xd8 || data[2] != 0xff) return "not a JPEG file";
  JpegDecoder d;
  bool cmyk = false;
  if (!jpegStart(d.cinfo, d.errors, data, size, cmyk)) return d.errors.message;
  if (cmyk) {
    unsupported = true;
    return "";
  }
  const int w = int(d.cinfo.output_width), h = int(d.cinfo.output_height), nch = d.cinfo.output_components;
  std::string refused = imageSizeProblem(w, h, nch);
  if (refused.empty() && check) refused = check(w, h, nch);
  if (!refused.empty()) return refused;
  const std::size_t rowBytes = std::size_t(w) * std::size_t(nch);
  std::vector<unsigned char> pixels(rowBytes * std::size_t(h));
  if (!jpegRows(d.cinfo, d.errors, pixels.data(), rowBytes)) return d.errors.message;
  out.width = w;
  out.height = h;
  out.pixelType = "uint8";
  out.channels = nch == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
  const std::size_t count = out.pixelCount();
  out.planes.assign(std::size_t(nch), std::vector<float>(count));
  // code / 255 as OpenImageIO's conversion gives it (code times the float 1 / 255).
  for (std::size_t p = 0; p < count; ++p)
    for (int c = 0; c < nch; ++c) out.planes[std::size_t(c)][p] = float(pixels[p * std::size_t(nch) + std::size_t(c)]) * (1.0f / 255.0f);
  return "";
}

}  // namespace montecl
