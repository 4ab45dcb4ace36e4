// cache_entry.cpp: encoding and verification of program-cache entries (see cache_entry.h).
#include "cl/cache_entry.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include "util/hash.h"

namespace montecl {
namespace {

constexpr char kCacheMagic[8] = {'M', 'C', 'L', 'P', 'R', 'G', '0', '2'};
constexpr std::size_t kHeader = 32;

std::uint64_t readU64(const std::vector<unsigned char>& data, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t(data[at + i]) << (8 * i);
  return v;
}
void putU64(unsigned char* out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out[i] = static_cast<unsigned char>(v >> (8 * i));
}
std::uint64_t checksum(const unsigned char* p, std::size_t n) {
  return fnv1a64(std::string(reinterpret_cast<const char*>(p), n));
}

}  // namespace

std::vector<unsigned char> encodeCacheEntry(std::uint64_t check, const std::vector<unsigned char>& bin) {
  std::vector<unsigned char> data(kHeader + bin.size());
  std::memcpy(data.data(), kCacheMagic, 8);
  putU64(data.data() + 8, check);
  putU64(data.data() + 16, bin.size());
  putU64(data.data() + 24, checksum(bin.data(), bin.size()));
  if (!bin.empty()) std::memcpy(data.data() + kHeader, bin.data(), bin.size());
  return data;
}

bool decodeCacheEntry(const std::vector<unsigned char>& data, std::uint64_t check,
                      std::vector<unsigned char>& bin) {
  if (data.size() <= kHeader || std::memcmp(data.data(), kCacheMagic, 8) != 0) return false;
  if (readU64(data, 8) != check || readU64(data, 16) != data.size() - kHeader) return false;
  if (readU64(data, 24) != checksum(data.data() + kHeader, data.size() - kHeader)) return false;
  bin.assign(data.begin() + kHeader, data.end());
  return true;
}

bool readCacheEntryFile(const std::string& path, std::uint64_t check, std::vector<unsigned char>& bin) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::vector<unsigned char> data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  return decodeCacheEntry(data, check, bin);
}

}  // namespace montecl
