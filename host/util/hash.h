// hash.h: a 64-bit FNV-1a hash, as hex, for cache keys.
#pragma once
#include <cstdint>
#include <string>

namespace montecl {
std::uint64_t fnv1a64(const std::string& data, std::uint64_t seed = 0xcbf29ce484222325ull);
std::string hex64(std::uint64_t v);
}  // namespace montecl
