// render_options.h: what one render is asked to do beside the scene: how (RenderOptions: wave
// sizes, stopping rules, adaptive sampling, what to record) and which part (RenderPart: pixels,
// the film to resume, the textures and triangles prepared beforehand). Apart from the wave loop
// (render/wavefront.h), so that its parts (the sample schedule) read them without including it.
// Reads and writes nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bvh/bvh_layout.h"
#include "image/film.h"
#include "render/wave_planner.h"

namespace montecl {

struct PreparedTriangles;  // render/wavefront.h
struct SceneTextures;      // texture/scene_textures.h

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
  // Called once the scene's device tables are built, before the first wave (the command line ends
  // its loading phase there: a signal then stops after a wave instead of ending the process).
  std::function<void()> wavesStart;
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
  // no second copy, unless keepTriangles); null: prepared here from scene.triangles.
  PreparedTriangles* triangles = nullptr;
  // Another render of the same triangles follows (a batch of views): the render copies their
  // tables instead of taking them, so *triangles stays whole for it.
  bool keepTriangles = false;
};

}  // namespace montecl
