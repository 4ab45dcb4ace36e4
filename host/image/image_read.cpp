// image_read.cpp: picks the reader of an image by its signature, else its name's extension (image_read.h).
#include "image/image_read.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/exr_layers.h"
#include "image/exr_read.h"
#include "image/hdr_read.h"
#include "image/jpeg_read.h"
#include "image/png_read.h"
#include "util/errors.h"

namespace montecl {
namespace {

enum class ImageReader { Png, Jpeg, Exr, Hdr, Other };

ImageReader readerOf(const std::string& name) {
  std::string ext = std::filesystem::path(name).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".png") return ImageReader::Png;
  if (ext == ".jpg" || ext == ".jpeg" || ext == ".jpe" || ext == ".jfif") return ImageReader::Jpeg;
  if (ext == ".exr" || ext == ".sxr" || ext == ".mxr") return ImageReader::Exr;  // OpenImageIO's EXR names
  if (ext == ".hdr" || ext == ".rgbe") return ImageReader::Hdr;
  return ImageReader::Other;
}

// The reader of an image whose encoding starts with head[0, n): its signature when it is a PNG or
// a JPEG (exporters name files by habit: a PNG called .jpg is common, and OpenImageIO looks at the
// content too), else name's extension (so a damaged .png still gets the PNG reader's message).
ImageReader readerOf(const std::string& name, const unsigned char* head, std::size_t n) {
  if (n >= 8 && std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0) return ImageReader::Png;
  if (n >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) return ImageReader::Jpeg;
  if (isExrSignature(head, n)) return ImageReader::Exr;
  if (isHdrSignature(head, n)) return ImageReader::Hdr;
  return readerOf(name);
}

// readerOf the file path from its first bytes (its extension when it cannot be read).
ImageReader readerOfFile(const std::string& path) {
  unsigned char head[16] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  return readerOf(path, head, std::size_t(in.gcount()));
}

// Decodes with montecl's own reader of format the bytes data[0 .. size), or (data null, an EXR or
// HDR file) the file name; false (out untouched) when OpenImageIO must (a CMYK JPEG, an EXR of
// unsigned integers). Throws InputError naming name.
bool decodeOwn(ImageReader format, const std::string& name, const unsigned char* data, std::size_t size,
               LayeredImage& out, const ImageSizeCheck& check) {
  bool unsupported = false;
  std::string why;
  switch (format) {
    case ImageReader::Png: why = decodePng(data, size, out, check); break;
    case ImageReader::Jpeg: why = decodeJpeg(data, size, out, check, unsupported); break;
    case ImageReader::Exr: why = decodeExr(name, data, size, out, check, unsupported); break;
    case ImageReader::Hdr: why = decodeHdr(name, data, size, out, check); break;
    case ImageReader::Other: return false;
  }
  if (!why.empty()) throwInputError(name, "", "cannot read image: " + why);
  return !unsupported;
}

// The readers that open a file themselves (OpenEXR reads only the parts it needs).
bool readsFileItself(ImageReader format) { return format == ImageReader::Exr || format == ImageReader::Hdr; }

}  // namespace

bool readsWithoutOiio(const std::string& path) { return readerOfFile(path) != ImageReader::Other; }

LayeredImage readImageFile(const std::string& path, const ImageSizeCheck& check) {
  const ImageReader format = readerOfFile(path);
  if (format == ImageReader::Other) return oiioRead(path, check);
  LayeredImage image;
  if (readsFileItself(format)) {
    if (decodeOwn(format, path, nullptr, 0, image, check)) return image;
    return oiioRead(path, check);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path, "", "cannot read image: cannot open the file");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throwInputError(path, "", "cannot read image: read error");
  if (decodeOwn(format, path, bytes.data(), bytes.size(), image, check)) return image;
  return oiioRead(path, check);
}

ImageSize readImageSize(const std::string& name, const std::vector<unsigned char>* bytes) {
  ImageSize size;
  const ImageSizeCheck capture = [&](int w, int h, int) -> std::string {
    size = ImageSize{w, h};
    return "only its size was asked for";
  };
  const auto attempt = [&](const auto& read) {
    try {
      read();
    } catch (const InputError&) {  // the capture's refusal, or a file that cannot be read
    }
  };
  if (bytes) {
    attempt([&] { readImageMemory(name, *bytes, capture); });
    return size;
  }
  const ImageReader format = readerOfFile(name);
  if (format != ImageReader::Other && !readsFileItself(format)) {
    // The header is at the start: a prefix of the file is enough unless metadata comes first.
    std::ifstream in(name, std::ios::binary);
    std::vector<unsigned char> prefix(256u << 10);
    in.read(reinterpret_cast<char*>(prefix.data()), std::streamsize(prefix.size()));
    prefix.resize(std::size_t(in.gcount()));
    LayeredImage unused;
    attempt([&] { decodeOwn(format, name, prefix.data(), prefix.size(), unused, capture); });
    if (size.width > 0) return size;
  }
  attempt([&] { readImageFile(name, capture); });
  return size;
}

LayeredImage readImageMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                             const ImageSizeCheck& check) {
  const ImageReader format = readerOf(name, bytes.data(), bytes.size());
  LayeredImage image;
  if (format != ImageReader::Other && decodeOwn(format, name, bytes.data(), bytes.size(), image, check)) return image;
  return oiioReadMemory(name, bytes, check);
}

}  // namespace montecl
