// memory_check.cpp: the image-size memory check (memory_check.h).
#include "render/memory_check.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "render/wave_buffers.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl {
namespace {

std::string gib(std::uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(1ull << 30));
  return buf;
}

}  // namespace

ImageMemory imageMemoryNeed(std::uint64_t pixels, bool aovs, std::uint64_t waveBytes) {
  ImageMemory m;
  // The film's buffers (render/wave_buffers.h) and the active pixel list; then the per-wave buffers.
  m.device = pixels * (filmBytesPerPixel(aovs) + sizeof(std::uint32_t)) + waveBytes;
  // The film read back (its buffers and the 64-bit sample counts), and the output: up to 7 float
  // planes (R, G, B, samples, var.R/G/B) + 7 AOV planes, plus the encoder's copy of them.
  m.host = pixels * (filmBytesPerPixel(aovs) + sizeof(std::uint64_t) + 2 * 4 * (7 + (aovs ? 7 : 0)));
  return m;
}

std::uint64_t hostMemoryBytes() {
  if (const char* limit = std::getenv("MONTECL_MEMORY_LIMIT")) {
    char* end = nullptr;
    unsigned long long v = std::strtoull(limit, &end, 10);
    if (end != limit && *end == '\0' && v > 0) return v;
  }
  const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return ~std::uint64_t(0);
  return std::uint64_t(pages) * std::uint64_t(pageSize);
}

std::string decodeMemoryRefusal(int width, int height, int channels, std::uint64_t extraBytesPerPixel) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const std::uint64_t need = pixels * (std::uint64_t(channels) * 8 + extraBytesPerPixel), has = hostMemoryBytes();
  if (need <= has) return "";
  return "declares " + std::to_string(width) + "x" + std::to_string(height) + " pixels, " + std::to_string(channels) +
         " channels: needs about " + gib(need) + " of memory to decode, this machine has " + gib(has);
}

std::string sceneMemoryRefusal(std::uint64_t triangles) {
  const std::uint64_t need = triangles * (sizeof(SceneTriangle) + 125), has = hostMemoryBytes();
  if (need <= has) return "";
  return "gives " + std::to_string(triangles) + " triangles: needs about " + gib(need) +
         " of memory (triangles and BVH), this machine has " + gib(has);
}

void checkImageMemory(const DeviceInfo& device, const std::string& scenePath, int width, int height, bool aovs,
                      std::uint64_t waveBytes) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const ImageMemory need = imageMemoryNeed(pixels, aovs, waveBytes);
  const std::string where = "image " + std::to_string(width) + "x" + std::to_string(height);
  const std::string what = aovs ? " (film, AOVs and output image)" : " (film and output image)";
  const std::uint64_t hostHas = hostMemoryBytes();
  // The host backend's buffers, and a CPU OpenCL device's (PoCL and Intel's runtime allocate them in
  // this machine's memory), come out of host memory too.
  const bool sharesHostMemory = device.isHost || device.isCpu;
  const std::uint64_t hostNeeds = need.host + (sharesHostMemory ? need.device : 0);
  if (hostNeeds > hostHas)
    throwInputError(scenePath, where,
                    "needs about " + gib(hostNeeds) + " of memory" + what + ", this machine has " + gib(hostHas) +
                        "; use a smaller --width/--height");
  if (!device.isHost && device.globalMemBytes > 0 && need.device > device.globalMemBytes)
    throwInputError(scenePath, where,
                    "needs about " + gib(need.device) + " of device memory" + what + ", " + device.name + " has " +
                        gib(device.globalMemBytes) + "; use a smaller --width/--height");
}

}  // namespace montecl
