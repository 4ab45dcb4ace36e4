// host_memory.cpp: this machine's memory and the expansion checks (host_memory.h).
#include "util/host_memory.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace montecl {

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

std::string gibText(std::uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(1ull << 30));
  return buf;
}

std::string decodeMemoryRefusal(int width, int height, int channels, std::uint64_t extraBytesPerPixel) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const std::uint64_t need = pixels * (std::uint64_t(channels) * 8 + extraBytesPerPixel), has = hostMemoryBytes();
  if (need <= has) return "";
  return "declares " + std::to_string(width) + "x" + std::to_string(height) + " pixels, " + std::to_string(channels) +
         " channels: needs about " + gibText(need) + " of memory to decode, this machine has " + gibText(has);
}

std::string sceneMemoryRefusal(std::uint64_t triangles, std::uint64_t triangleBytes) {
  const std::uint64_t need = triangles * (triangleBytes + 125), has = hostMemoryBytes();
  if (need <= has) return "";
  return "gives " + std::to_string(triangles) + " triangles: needs about " + gibText(need) +
         " of memory (triangles and BVH), this machine has " + gibText(has);
}

}  // namespace montecl
