// cache_entry.h: the on-disk format of one program-cache entry (program_cache.cpp), without
// OpenCL, so that it can be tested and fuzzed on its own (fuzz/fuzz_entries.cpp).
// Entry: 8-byte magic "MCLPRG02", then little-endian 64-bit words: the check (a second hash of the
// cache key, a collision guard for the 64-bit file name), the binary's size and its FNV-1a, then
// the program binary as CL_PROGRAM_BINARIES gave it. A truncated or corrupted binary crashed PoCL
// on load, on every later run: size and checksum are verified before the driver sees it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace montecl {

// The bytes of an entry holding bin under check.
std::vector<unsigned char> encodeCacheEntry(std::uint64_t check, const std::vector<unsigned char>& bin);

// Verifies an entry's bytes: true, with bin set to the program binary, when data is a well-formed
// entry for check; false (bin untouched) for anything else. Never throws on any bytes.
bool decodeCacheEntry(const std::vector<unsigned char>& data, std::uint64_t check,
                      std::vector<unsigned char>& bin);

// Reads the entry file at path and decodes it; false when it cannot be read or does not verify.
bool readCacheEntryFile(const std::string& path, std::uint64_t check, std::vector<unsigned char>& bin);

}  // namespace montecl
