// image_io.cpp: RGB image output by extension, always atomic: PNG through libpng, EXR through
// OpenEXR (exr_layers.h writeLayeredExr), PFM by hand.
#include "image/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>  // PATH_MAX, NAME_MAX
#include <cstring>
#include <filesystem>
#include <fstream>

#include "image/exr_layers.h"
#include "image/png_write.h"
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
    errno = 0;  // the failed write's reason (EFBIG past ulimit -f, ENOSPC, ...) for the message
    std::ofstream out(tmp, std::ios::binary);
    out << "PF\n" << width << " " << height << "\n-1.0\n";
    for (int y = height - 1; y >= 0; --y)
      out.write(reinterpret_cast<const char*>(&rgb[std::size_t(y) * width * 3]), std::streamsize(width) * 3 * 4);
    if (!out.flush()) throw RuntimeError("cannot write " + path + (errno ? std::string(": ") + std::strerror(errno) : ""));
  });
}

}  // namespace

void checkOutputPath(const std::string& path) {
  // Over the system's limits every later step fails with ENAMETOOLONG (a filesystem exception,
  // exit 1); the path itself is shortened in the message.
  if (path.size() >= PATH_MAX)
    throwInputError(path.substr(0, 40) + "..." + path.substr(path.size() - 20), "", "output path is " + std::to_string(path.size()) + " characters, over the limit of " +
                                   std::to_string(PATH_MAX - 1));
  for (const std::filesystem::path& part : std::filesystem::path(path))
    if (part.native().size() > NAME_MAX)
      throwInputError(path, "", "a name in the output path is " + std::to_string(part.native().size()) +
                                     " characters, over the limit of " + std::to_string(NAME_MAX));
  std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr" && ext != ".pfm")
    throwInputError(path, "", "unsupported image format '" + ext + "' (use .png, .exr or .pfm)");
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throwInputError(path, "", "output folder '" + dir.string() + "' does not exist");
}

void writeRgbImage(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  std::string ext = lowerExtension(path);
  if (ext == ".pfm") return writePfm(path, width, height, rgb);
  if (ext == ".png")
    return writeAtomically(path, [&](const std::string& tmp) { writePngSrgb(tmp, path, width, height, rgb); });
  LayeredImage image;
  image.width = width;
  image.height = height;
  for (int c = 0; c < 3; ++c) {
    std::vector<float> plane(std::size_t(width) * height);
    for (std::size_t p = 0; p < plane.size(); ++p) plane[p] = rgb[p * 3 + c];
    image.set(channel::kMean[c], std::move(plane));
  }
  writeLayeredExr(path, image);
}

}  // namespace montecl
