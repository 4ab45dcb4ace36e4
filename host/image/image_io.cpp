// image_io.cpp: OpenImageIO output (atomic, by extension) and input of RGB float images.
#include "image/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "util/atomic_file.h"
#include "util/errors.h"

namespace montecl {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Portable float map (little-endian, rows bottom to top). Written by hand: Debian's OpenImageIO
// 2.4 has no PFM writer ("could not find a format writer").
void writePfm(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << "PF\n" << width << " " << height << "\n-1.0\n";
    for (int y = height - 1; y >= 0; --y)
      out.write(reinterpret_cast<const char*>(&rgb[std::size_t(y) * width * 3]), std::streamsize(width) * 3 * 4);
    if (!out.flush()) throw RuntimeError("cannot write " + path);
  });
}

}  // namespace

void checkOutputPath(const std::string& path) {
  std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr" && ext != ".pfm")
    throwInputError(path, "", "unsupported image format '" + ext + "' (use .png, .exr or .pfm)");
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throwInputError(path, "", "output folder '" + dir.string() + "' does not exist");
}

void writeRgbImage(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  using namespace OIIO;
  std::string ext = lowerExtension(path);
  if (ext == ".pfm") return writePfm(path, width, height, rgb);
  ImageSpec spec(width, height, 3, TypeDesc::FLOAT);
  ImageBuf linear(spec);
  linear.set_pixels(ROI(0, width, 0, height, 0, 1, 0, 3), TypeDesc::FLOAT, rgb.data());
  ImageBuf out;
  if (ext == ".png") {
    // sRGB transfer, then OpenImageIO clamps to [0, 1] when converting to 8 bits.
    if (!ImageBufAlgo::colorconvert(out, linear, "linear", "sRGB"))
      throw RuntimeError("colour conversion for " + path + " failed: " + out.geterror());
    out.specmod().attribute("oiio:ColorSpace", "sRGB");
  } else {
    out.copy(linear);
  }
  TypeDesc format = ext == ".png" ? TypeDesc::UINT8 : TypeDesc::FLOAT;
  writeAtomically(path, [&](const std::string& tmp) {
    out.set_write_format(format);
    if (!out.write(tmp))
      throw RuntimeError("cannot write " + path + ": " + out.geterror());
  });
}

}  // namespace montecl
