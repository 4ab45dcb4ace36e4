// cache_entry.cpp: encoding and verification of program-cache entries (see cache_entry.h).
#include "cl/cache_entry.h"

#include <cstring>
#include <fstream>
#include <iterator>

namespace montecl {
namespace {
constexpr char kMagic[8] = {'M', 'C', 'L', 'P', 'R', 'G', '0', '1'};
constexpr std::size_t kHeader = 16;
}  // namespace

std::vector<unsigned char> encodeCacheEntry(std::uint64_t check, const std::vector<unsigned char>& bin) {
  std::vector<unsigned char> data(kHeader + bin.size());
  std::memcpy(data.data(), kMagic, 8);
  for (int i = 0; i < 8; ++i) data[8 + i] = static_cast<unsigned char>(check >> (8 * i));
  if (!bin.empty()) std::memcpy(data.data() + kHeader, bin.data(), bin.size());
  return data;
}

bool decodeCacheEntry(const std::vector<unsigned char>& data, std::uint64_t check,
                      std::vector<unsigned char>& bin) {
  if (data.size() <= kHeader || std::memcmp(data.data(), kMagic, 8) != 0) return false;
  std::uint64_t stored = 0;
  for (int i = 0; i < 8; ++i) stored |= std::uint64_t(data[8 + i]) << (8 * i);
  if (stored != check) return false;
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
