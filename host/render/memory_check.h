// memory_check.h: before anything image-sized is allocated, the image's per-pixel state is held
// against the memory there is, so a too-large image is a one-line error saying how much it needs
// (not a 30 s run into std::bad_alloc or a raw CL_INVALID_BUFFER_SIZE).
#pragma once
#include <cstdint>
#include <string>

#include "cl/devices.h"
#include "util/host_memory.h"  // hostMemoryBytes, and the checks before expanding inputs

namespace montecl {

struct ImageMemory {
  std::uint64_t device = 0;  // device buffers: film (4 float4), AOV sums (2 float4), active list, wave
  std::uint64_t host = 0;    // host copies: the film read back, AOVs, the output image being written
};

// Bytes an image of `pixels` needs with waveBytes of per-wave buffers (already budgeted).
// splits: the sobol sampler's sub-sequences per pixel (WaveShape::splits; 0 or 1: none).
ImageMemory imageMemoryNeed(std::uint64_t pixels, bool aovs, std::uint64_t waveBytes, std::uint64_t splits = 0);

// Throws InputError "<scene>: image WxH: needs about X GiB ..., <where> has Y GiB" when the need
// exceeds host memory (host backend and CPU OpenCL devices: device + host) or the device's global memory.
void checkImageMemory(const DeviceInfo& device, const std::string& scenePath, int width, int height, bool aovs,
                      std::uint64_t waveBytes, std::uint64_t splits = 0);

}  // namespace montecl
