// hash.cpp: 64-bit FNV-1a over a byte string and its 16-digit lowercase hex form (cache keys).
#include "util/hash.h"

namespace montecl {

std::uint64_t fnv1a64(const std::string& data, std::uint64_t seed) {
  Fnv1a64 h(seed);
  h.add(data);
  return h.value();
}

void Fnv1a64::add(const void* data, std::size_t size) {
  const unsigned char* c = static_cast<const unsigned char*>(data);
  std::uint64_t h = h_;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= c[i];
    h *= 0x100000001b3ull;
  }
  h_ = h;
}

std::string hex64(std::uint64_t v) {
  static const char digits[] = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) s[i] = digits[v & 0xf];
  return s;
}

}  // namespace montecl
