// wavefront.h: the wavefront renderer. Uploads the BVH, then per wave: generate -> intersect ->
// shade -> intersect_shadow -> accumulate, each a kernel of kernels/montecl.cl on an OpenCL device,
// or the same stage functions run on the CPU when the device is the host backend (DeviceInfo::isHost,
// `--device host`). Waves are sized from the measured rate (render/wave_planner.h) up to an
// allocated cap; the result does not depend on wave or work-group size, and has been bit-identical
// across every device measured (`montecl conformance` against the host backend: max difference 0;
// it passes a pixel channel within 1e-5 relative, and requires equal sample counts).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "image/film.h"
#include "render/render_options.h"
#include "render/stage_profile.h"
#include "scene/scene.h"
#include "texture/scene_textures.h"

namespace montecl {

// The default cap on a wave's items (RenderOptions::maxWaveItems 0), from a sweep of wave sizes
// on Sponza (docs/performance.md, "Wave size and memory"): on CPUs (and the host backend) 8192
// items per compute unit, at least 16384: a wave's state then stays in the caches, and larger
// waves were slower and cost memory; on GPUs 2^20 items, enough to fill one. Path tracing on
// CPUs: four times the CPU cap (fewer waves, so fewer of the per-bounce launches and read-backs;
// bench/journal/lanes.md, "Sample blocks and path waves").
std::uint64_t defaultMaxWaveItems(const DeviceInfo& device, bool path = false);

// What the renderer reads of a scene's triangles, built once: the per-triangle attributes in BVH
// order (render/triangle_shading.h) and the ray-offset scale (render/frame_params.h). A caller that
// prepares them can free the scene's triangles before rendering (montecl render does: the peak
// memory then lacks their size); the BVH and the textures are read to the end.
struct PreparedTriangles {
  std::vector<TriangleShading> shading;
  std::vector<float4> vertexColors;  // buildVertexColors (empty: no triangle has any)
  std::vector<float4> tangents;      // buildVertexTangents (empty: no triangle has any)
  float offsetScale = 1.0f;
};
PreparedTriangles prepareTriangles(const Scene& scene, const Bvh& bvh);

// The textures' byte budget on a device when the user sets none: 1 GiB, at most the device's
// largest allocation (the host backend has no such limit).
std::uint64_t defaultTextureBudget(const DeviceInfo& device);

struct RenderStats {
  double seconds = 0.0;         // wall time of the wave loop (kernels + transfers)
  std::uint64_t cameraRays = 0;   // camera rays, and the BRDF / path continuation rays
  std::uint64_t shadowRays = 0;
  std::uint64_t nanRays = 0;      // rays with a NaN/inf origin or direction, treated as misses
  std::uint64_t waves = 0;
  std::uint64_t waveSize = 0;     // the allocated wave (the largest a wave can be)
  std::uint64_t samples = 0;      // pixel samples rendered
  std::uint64_t rounds = 0;       // adaptive rounds (1 without adaptive sampling)
  std::uint64_t converged = 0;    // adaptive: pixels that met the target error
  bool stoppedEarly = false;      // the time limit or an interrupt ended the render
  StageProfile profile;           // with RenderOptions::profile: each stage's summed time
  std::vector<std::uint64_t> pathSurvivors;  // --integrator path: [b] paths shaded at bounce b
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
  Film render(const Scene& scene, const Bvh& bvh, RenderStats& stats, const ProgressFn& progress = {},
              const RenderPart& part = {});

  bool programFromCache() const;
  double programBuildMs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace montecl
