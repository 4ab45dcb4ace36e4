// host_memory.h: how much memory this machine has, and the checks that refuse an input before
// it is expanded into more than that (an image file's declared size, a scene's triangle count).
// Reads sysconf or MONTECL_MEMORY_LIMIT; writes nothing. Kept free of OpenCL so the fuzzed loaders
// link it alone.
#pragma once
#include <cstdint>
#include <string>

namespace montecl {

// Physical memory of this machine (sysconf), or MONTECL_MEMORY_LIMIT (bytes) when that is set.
std::uint64_t hostMemoryBytes();

// "1.5 GiB"
std::string gibText(std::uint64_t bytes);

// Why an image file declaring width x height pixels of `channels` channels must not be decoded:
// decoding holds 8 bytes per value (a reader's interleaved floats and montecl's planes), and
// the caller keeps extraBytesPerPixel more; "" when that fits hostMemoryBytes(). For
// readLayeredImage's size check (image/oiio_loader.h), so a tiny file cannot cost gigabytes.
std::string decodeMemoryRefusal(int width, int height, int channels, std::uint64_t extraBytesPerPixel);

// Why a scene of `triangles` triangles must not be loaded: each costs triangleBytes (the caller's
// SceneTriangle) and about 125 bytes at the BVH build's peak (bvh/bvh_build.cpp); "" when that
// fits hostMemoryBytes(). Otherwise "gives N triangles: needs about X GiB of memory ..., this
// machine has Y GiB".
std::string sceneMemoryRefusal(std::uint64_t triangles, std::uint64_t triangleBytes);

}  // namespace montecl
