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
#include "render/stage_profile.h"
#include "render/wave_planner.h"
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

struct RenderOptions {
  // Wave items (pixel samples). 0: the buffers hold maxWaveItems (0: defaultMaxWaveItems; or what
  // memoryBudget allows, if less) and each wave is sized by `planner` from the measured rate.
  // Set: every wave has this size, except with timeLimit, when it is the cap the planner sizes
  // waves under.
  std::uint64_t waveSize = 0;
  std::uint64_t maxWaveItems = 0;
  std::uint64_t memoryBudget = 256ull << 20;   // bytes of per-wave buffers when waveSize is 0
  WavePlanner planner;
  std::size_t workGroupSize = 0;               // 0: min(CL_KERNEL_WORK_GROUP_SIZE, 64)
  BvhLayout bvhLayout = BvhLayout::Auto;        // BVH the kernels traverse (bvh/bvh_layout.h)
  unsigned lanes = 0;                          // packet stages' width W (0: the device's; cl/device_tuning.h)
  std::uint32_t firstSample = 0;               // render sample indices firstSample .. + spp - 1
  bool verbose = false;
  // Stops at this many seconds (0: no limit): waves are planned so the last one ends there.
  double timeLimit = 0.0;
  // Stops after the current wave once *interrupt is non-zero (e.g. set by a SIGINT handler).
  const volatile int* interrupt = nullptr;
  // Adaptive sampling when targetError > 0: every pixel gets minSpp samples, then rounds double
  // the samples of the pixels whose relative standard error exceeds targetError, up to maxSpp
  // (the scene's spp is ignored). Relative error: stderr / max(mean luminance, errorFloor).
  double targetError = 0.0;
  int minSpp = 16;
  int maxSpp = 1024;
  double errorFloor = 0.01;
  bool profile = false;  // time every stage launch into RenderStats::profile (--profile)
  bool aovs = false;  // also accumulate first-hit albedo, normal and depth (Film::aovSum)
  // What else changes a pixel beside the settings table and the scene (the texture budget's dropped
  // levels: texture/texture_identity.h); part of the checkpoint key, as of the provenance.
  std::string identityExtra;
  // Run a wave as one fused launch where the integrator has a fused stage and the device runs
  // packets (kernels/stages/wave_fused.h); false: every stage its own launch (--no-fuse).
  bool fuseWaves = true;
};

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

// What one render call covers, beside the scene: decided per call (by a job: job/job.h), so the
// renderer can be built before or after whoever decides it.
struct RenderPart {
  // The pixels to render, ascending (empty: all): one rank's share of an MPI job. Each pixel's
  // result depends only on its own samples, so any subset renders bit-identically.
  std::vector<std::uint32_t> pixels;
  // Film state to continue from (a checkpoint, render/checkpoint.h): every pixel resumes at its
  // own count, so the result is bit-identical to a render that never stopped. Null: a clear film.
  const Film* initialFilm = nullptr;
  // Called after every wave's progress callback; readFilm() reads the film state as of that wave.
  std::function<void(const std::function<Film()>& readFilm)> afterWave;
  // The scene's decoded textures (texture/scene_textures.h); null: loaded here under
  // defaultTextureBudget when a material names a texture (warnings dropped).
  const SceneTextures* textures = nullptr;
  // The scene's triangles as prepared beforehand (the render moves the shading table out of it:
  // no second copy); null: prepared here from scene.triangles.
  PreparedTriangles* triangles = nullptr;
};

// Relative standard error of pixel p's mean luminance (infinite below 2 samples).
double relativeStandardError(const Film& film, std::size_t p, double errorFloor);

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
