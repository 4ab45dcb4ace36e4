// wavefront.h: the wavefront renderer. Uploads the BVH, then per wave: generate -> intersect ->
// shade -> intersect_shadow -> accumulate, each a kernel of kernels/montecl.cl on an OpenCL device,
// or the same stage functions run on the CPU when the device is the host backend (DeviceInfo::isHost,
// `--device host`). Waves are bounded by a memory budget; the result does not depend on wave or
// work-group size, and agrees across devices to about 1e-6 relative (see `montecl conformance`).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "image/film.h"
#include "scene/scene.h"

namespace montecl {

struct RenderOptions {
  std::uint64_t waveSize = 0;                  // wave items (pixel samples); 0: from memoryBudget
  std::uint64_t memoryBudget = 256ull << 20;   // bytes of per-wave buffers when waveSize is 0
  std::size_t workGroupSize = 0;               // 0: min(CL_KERNEL_WORK_GROUP_SIZE, 64)
  std::uint32_t firstSample = 0;               // render sample indices firstSample .. + spp - 1
  bool verbose = false;
};

struct RenderStats {
  double seconds = 0.0;         // wall time of the wave loop (kernels + transfers)
  std::uint64_t cameraRays = 0;
  std::uint64_t shadowRays = 0;
  std::uint64_t waves = 0;
  std::uint64_t waveSize = 0;
  std::uint64_t raysTraced() const { return cameraRays + shadowRays; }
};

// Reports progress after each wave: samples done, samples total, stats so far.
using ProgressFn = std::function<void(std::uint64_t done, std::uint64_t total, const RenderStats&)>;

class WavefrontRenderer {
 public:
  WavefrontRenderer(const DeviceInfo& device, const RenderOptions& options);
  ~WavefrontRenderer();
  WavefrontRenderer(const WavefrontRenderer&) = delete;
  WavefrontRenderer& operator=(const WavefrontRenderer&) = delete;

  // Renders scene (its camera and render settings) with the given BVH of scene.triangles.
  Film render(const Scene& scene, const Bvh& bvh, RenderStats& stats, const ProgressFn& progress = {});

  bool programFromCache() const;
  double programBuildMs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace montecl
