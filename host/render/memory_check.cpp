// memory_check.cpp: the image-size memory check (memory_check.h).
#include "render/memory_check.h"

#include "render/wave_buffers.h"
#include "util/errors.h"

namespace montecl {
ImageMemory imageMemoryNeed(std::uint64_t pixels, bool aovs, std::uint64_t waveBytes, std::uint64_t splits) {
  ImageMemory m;
  // The film's buffers (render/wave_buffers.h) and the active pixel list; then the per-wave buffers.
  m.device = pixels * (filmBytesPerPixel(aovs, splits) + sizeof(std::uint32_t)) + waveBytes;
  // The film read back (its buffers and the 64-bit sample counts), and the output: up to 7 float
  // planes (R, G, B, samples, var.R/G/B) + 10 AOV planes (albedo, N, Z, emission; + 4 per sub-sequence and err.R/G/B),
  // plus the encoder's copy of them.
  const std::uint64_t splitPlanes = splits > 1 ? 4 * splits + 3 : 0;
  m.host = pixels * (filmBytesPerPixel(aovs, splits) + sizeof(std::uint64_t) + 2 * 4 * (7 + (aovs ? 10 : 0) + splitPlanes));
  return m;
}

void checkImageMemory(const DeviceInfo& device, const std::string& scenePath, int width, int height, bool aovs,
                      std::uint64_t waveBytes, std::uint64_t splits) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const ImageMemory need = imageMemoryNeed(pixels, aovs, waveBytes, splits);
  const std::string where = "image " + std::to_string(width) + "x" + std::to_string(height);
  const std::string what = aovs ? " (film, AOVs and output image)" : " (film and output image)";
  const std::uint64_t hostHas = hostMemoryBytes();
  // The host backend's buffers, and a CPU OpenCL device's (PoCL and Intel's runtime allocate them in
  // this machine's memory), come out of host memory too.
  const bool sharesHostMemory = device.isHost || device.isCpu;
  const std::uint64_t hostNeeds = need.host + (sharesHostMemory ? need.device : 0);
  if (hostNeeds > hostHas)
    throwInputError(scenePath, where,
                    "needs about " + gibText(hostNeeds) + " of memory" + what + ", this machine has " + gibText(hostHas) +
                        "; use a smaller --width/--height");
  if (!device.isHost && device.globalMemBytes > 0 && need.device > device.globalMemBytes)
    throwInputError(scenePath, where,
                    "needs about " + gibText(need.device) + " of device memory" + what + ", " + device.name + " has " +
                        gibText(device.globalMemBytes) + "; use a smaller --width/--height");
}

}  // namespace montecl
