// png_read.cpp: decodes an encoded PNG held in memory into float planes with libpng (png_read.h).
#include "image/png_read.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "image/exr_layers.h"
#include "image/image_limits.h"

namespace montecl {
namespace {

struct PngSource {
  const unsigned char* data;
  std::size_t size, pos;
  char message[256];  // libpng's error, kept for the one line the caller reports
};

void pngReadBytes(png_structp png, png_bytep out, png_size_t n) {
  PngSource* s = static_cast<PngSource*>(png_get_io_ptr(png));
  if (n > s->size - s->pos) png_error(png, "file is truncated");
  std::memcpy(out, s->data + s->pos, n);
  s->pos += n;
}

// libpng's errors longjmp back to decodePng's setjmp (never return into libpng); its warnings
// (a bad ancillary chunk, which it skips) are not the caller's concern.
[[noreturn]] void pngFail(png_structp png, png_const_charp msg) {
  PngSource* s = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(s->message, sizeof s->message, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}
void pngQuiet(png_structp, png_const_charp) {}

// The planes from interleaved 8- or 16-bit rows: code / max, as OpenImageIO's conversion gives it
// (code times the float 1 / max).
void pngToPlanes(const std::vector<unsigned char>& pixels, int bits, std::size_t count, std::size_t nch,
              LayeredImage& out) {
  const float scale = bits == 16 ? 1.0f / 65535.0f : 1.0f / 255.0f;
  out.planes.assign(nch, std::vector<float>(count));
  for (std::size_t p = 0; p < count; ++p)
    for (std::size_t c = 0; c < nch; ++c) {
      const std::size_t i = p * nch + c;
      const unsigned code = bits == 16 ? unsigned(pixels[2 * i]) << 8 | pixels[2 * i + 1] : pixels[i];
      out.planes[c][p] = float(code) * scale;
    }
}

// The two steps of a decode that call into libpng, each under its own setjmp and holding no C++
// object (a longjmp skips no destructor, and clobbers nothing the caller reads): false after an
// error, its message in the source's message.
bool pngStart(png_structp png, png_infop info, PngSource& src) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, &src, pngReadBytes);
  png_read_info(png, info);
  // OpenImageIO's PNG reader: 1-, 2- and 4-bit grey to 8 bits, the palette to RGB, tRNS to an
  // alpha channel; samples as stored (no gamma), 16-bit kept; alpha never premultiplied.
  png_set_expand(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return true;
}

bool pngRows(png_structp png, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

// Owns libpng's read and info structs: destroyed whichever way decodePng returns.
struct PngDecoder {
  png_structp png = nullptr;
  png_infop info = nullptr;
  explicit PngDecoder(PngSource& src) {
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, pngFail, pngQuiet);
    if (png) info = png_create_info_struct(png);
  }
  ~PngDecoder() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  }
  PngDecoder(const PngDecoder&) = delete;
  PngDecoder& operator=(const PngDecoder&) = delete;
};

}  // namespace

std::string decodePng(const unsigned char* data, std::size_t size, LayeredImage& out, const ImageSizeCheck& check) {
  out = LayeredImage{};
  if (size < 8 || png_sig_cmp(data, 0, 8) != 0) return "not a PNG file";
  PngSource src{data, size, 0, {0}};
  PngDecoder d(src);
  if (!d.png || !d.info) return "cannot create a PNG reader";
  if (!pngStart(d.png, d.info, src)) return src.message;
  const png_uint_32 w = png_get_image_width(d.png, d.info), h = png_get_image_height(d.png, d.info);
  const int bits = png_get_bit_depth(d.png, d.info);
  const int nch = png_get_channels(d.png, d.info);
  std::string refused = imageSizeProblem(long(w), long(h), nch, png_get_x_offset_pixels(d.png, d.info),
                                         png_get_y_offset_pixels(d.png, d.info));
  if (refused.empty() && check) refused = check(int(w), int(h), nch);
  if (!refused.empty()) return refused;
  const std::size_t rowBytes = png_get_rowbytes(d.png, d.info);
  std::vector<unsigned char> pixels(rowBytes * h);
  std::vector<png_bytep> rows(h);
  for (png_uint_32 y = 0; y < h; ++y) rows[y] = pixels.data() + y * rowBytes;
  if (!pngRows(d.png, rows.data())) return src.message;
  out.width = int(w);
  out.height = int(h);
  out.pixelType = bits == 16 ? "uint16" : "uint8";
  out.channels = nch == 1 ? std::vector<std::string>{"Y"}
                 : nch == 2 ? std::vector<std::string>{"Y", "A"}
                 : nch == 3 ? std::vector<std::string>{"R", "G", "B"}
                            : std::vector<std::string>{"R", "G", "B", "A"};
  pngToPlanes(pixels, bits, out.pixelCount(), std::size_t(nch), out);
  return "";
}

}  // namespace montecl
