// hdr_read.cpp: a Radiance RGBE file or encoded bytes -> float planes with stb_image (hdr_read.h).
#include "image/hdr_read.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

// Only the Radiance decoder of stb_image is compiled in (PNG and JPEG have their own libraries),
// reading from memory only, with its longer error messages, and every function static:
// libtinygltf.so binds stbi_* by name (to libstb's full decoder), and an exported HDR-only copy in
// the executable would take its place.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include "image/exr_layers.h"
#include "image/image_limits.h"

namespace montecl {
namespace {

// stb_image reads through these callbacks so that a read past the end is seen: stb_image itself
// gives zeros there, so a truncated flat file would decode with a black bottom, and a run-length
// encoded one would spin forever (a zero count copies nothing). Past the end the callbacks give
// newlines instead: a header line ends, a run-length count of 10 advances a row or is refused, so
// every decode ends, and pastEnd says the file was truncated.
struct HdrSource {
  const unsigned char* data;
  std::size_t size, pos;
  bool pastEnd;
};

int hdrRead(void* user, char* out, int n) {
  HdrSource& s = *static_cast<HdrSource*>(user);
  if (n <= 0) return 0;
  const std::size_t k = std::min(std::size_t(n), s.size - s.pos);
  std::memcpy(out, s.data + s.pos, k);
  s.pos += k;
  if (k > 0) return int(k);
  s.pastEnd = true;
  std::memset(out, '\n', std::size_t(n));
  return n;
}
void hdrSkip(void* user, int n) {
  HdrSource& s = *static_cast<HdrSource*>(user);
  if (n < 0) s.pos -= std::min(s.pos, std::size_t(-n));
  else s.pos += std::min(std::size_t(n), s.size - s.pos);
}
int hdrEof(void* user) {
  const HdrSource& s = *static_cast<const HdrSource*>(user);
  return s.pos >= s.size;
}
const stbi_io_callbacks kHdrCallbacks = {hdrRead, hdrSkip, hdrEof};

std::string decodeHdrBytes(const unsigned char* data, std::size_t size, LayeredImage& out,
                           const ImageSizeCheck& check) {
  if (!isHdrSignature(data, size)) return "not a Radiance HDR file";
  if (size > std::size_t(INT32_MAX)) return "file is over 2 GiB";
  int w = 0, h = 0, nch = 0;
  if (!stbi_info_from_memory(data, int(size), &w, &h, &nch)) return stbi_failure_reason();
  std::string refused = imageSizeProblem(w, h, 3);
  if (refused.empty() && check) refused = check(w, h, 3);
  if (!refused.empty()) return refused;
  HdrSource src{data, size, 0, false};
  const std::unique_ptr<float, void (*)(void*)> pixels(
      stbi_loadf_from_callbacks(&kHdrCallbacks, &src, &w, &h, &nch, 3), stbi_image_free);
  if (!pixels) return stbi_failure_reason();
  if (src.pastEnd) return "file is truncated";
  out.width = w;
  out.height = h;
  out.pixelType = "float";
  out.channels = {"R", "G", "B"};
  const std::size_t count = out.pixelCount();
  out.planes.assign(3, std::vector<float>(count));
  for (std::size_t p = 0; p < count; ++p)
    for (std::size_t c = 0; c < 3; ++c) out.planes[c][p] = pixels.get()[p * 3 + c];
  return "";
}

}  // namespace

bool isHdrSignature(const unsigned char* data, std::size_t size) {
  const auto starts = [&](const char* s) { return size >= std::strlen(s) && std::memcmp(data, s, std::strlen(s)) == 0; };
  return starts("#?RADIANCE\n") || starts("#?RGBE\n");
}

std::string decodeHdr(const std::string& path, const unsigned char* data, std::size_t size, LayeredImage& out,
                      const ImageSizeCheck& check) {
  out = LayeredImage{};
  if (data) return decodeHdrBytes(data, size, out, check);
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot open the file";
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return "read error";
  const std::string why = decodeHdrBytes(bytes.data(), bytes.size(), out, check);
  if (!why.empty()) out = LayeredImage{};
  return why;
}

}  // namespace montecl
