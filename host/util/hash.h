// hash.h: a 64-bit FNV-1a hash, as hex, for cache keys.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace montecl {
std::uint64_t fnv1a64(const std::string& data, std::uint64_t seed = 0xcbf29ce484222325ull);

// FNV-1a fed piece by piece: value() equals fnv1a64 of the pieces' concatenation, without holding
// it (a scene's triangles are hashed in place, not copied into a string first).
class Fnv1a64 {
 public:
  explicit Fnv1a64(std::uint64_t seed = 0xcbf29ce484222325ull) : h_(seed) {}
  void add(const void* data, std::size_t size);
  void add(const std::string& s) { add(s.data(), s.size()); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_;
};

std::string hex64(std::uint64_t v);
}  // namespace montecl
