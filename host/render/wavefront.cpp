// wavefront.cpp: the render loop, one for every backend (render/stage_runner.h: OpenCL kernels or
// the host's C++ loops). Sizes the wave, uploads once, then per wave: reset the queue counters,
// generate -> intersect -> shade_ao | (shade_direct -> intersect bounce -> shade_direct_hit) ->
// intersect_shadow -> accumulate; the host never reads a queue count back to size a launch.
#include "render/wavefront.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

#include "render/stage_runner.h"
#include "render/emitters.h"
#include "render/frame_params.h"
#include "render/memory_check.h"
#include "util/errors.h"

namespace montecl {
namespace {

// Bytes of per-wave buffers for one pixel sample with `slots` occlusion queries.
std::uint64_t bytesPerItem(std::uint32_t slots, bool bounce, bool aovs) {
  return sizeof(Ray) + sizeof(Hit) + sizeof(float4) + slots * (sizeof(float4) + sizeof(ShadowWork)) +
         (bounce ? sizeof(Ray) + sizeof(Hit) : 0) + (aovs ? 2 * sizeof(float4) : 0);
}

}  // namespace

struct WavefrontRenderer::Impl {
  Impl(const DeviceInfo& device, const RenderOptions& opts)
      : options(opts), device(device), runner(makeStageRunner(device, opts.workGroupSize, opts.bvhLayout)) {}
  RenderOptions options;
  DeviceInfo device;
  std::unique_ptr<StageRunner> runner;
};

WavefrontRenderer::WavefrontRenderer(const DeviceInfo& device, const RenderOptions& options)
    : impl_(std::make_unique<Impl>(device, options)) {}

WavefrontRenderer::~WavefrontRenderer() = default;

bool WavefrontRenderer::programFromCache() const { return impl_->runner->programFromCache(); }
double WavefrontRenderer::programBuildMs() const { return impl_->runner->programBuildMs(); }

namespace {

std::vector<Material> deviceMaterials(const std::vector<MaterialDesc>& materials) {
  std::vector<Material> out;
  for (const MaterialDesc& m : materials) out.push_back({glm::vec4(m.albedo, 0.0f), glm::vec4(m.emission, m.twoSidedEmission ? 1.0f : 0.0f)});
  return out;
}

}  // namespace

Film WavefrontRenderer::render(const Scene& scene, const Bvh& bvh, RenderStats& stats,
                               const ProgressFn& progress) {
  Impl& m = *impl_;
  StageRunner& run = *m.runner;
  const bool direct = scene.render.integrator == Integrator::Direct;
  const std::uint32_t slots = direct ? std::uint32_t(scene.render.lightSamples) + 1 : 1;
  FrameParams frame = makeFrameParams(scene.camera, scene.render, slots);
  const EmitterTable emitters = direct ? buildEmitterTable(bvh, scene.materials) : EmitterTable{};
  frame.emitterCount = uint(emitters.emitters.size());
  frame.emitterPower = emitters.totalPower;
  const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
  const std::uint64_t total = pixels * std::uint64_t(scene.render.spp);

  // Wave size: the memory budget, the device's largest allocation, and 32-bit item indices.
  const std::uint64_t maxAlloc = run.maxAllocBytes();
  std::uint64_t wave = m.options.waveSize;
  if (wave == 0) wave = std::max<std::uint64_t>(1, m.options.memoryBudget / bytesPerItem(slots, direct, m.options.aovs));
  wave = std::min<std::uint64_t>(wave, maxAlloc / (slots * sizeof(ShadowWork)));
  wave = std::min<std::uint64_t>(wave, 0xffffffffull / slots);
  wave = std::max<std::uint64_t>(1, std::min(wave, total));
  checkImageMemory(m.device, scene.path, scene.camera.width, scene.camera.height, m.options.aovs,
                   wave * bytesPerItem(slots, direct, m.options.aovs));
  for (std::uint64_t bytes : {pixels * sizeof(float4), std::uint64_t(bvhNodeBytes(bvh, run.bvhLayout())),
                              bvh.triangles.size() * sizeof(Triangle)})
    if (bytes > maxAlloc)
      throw RuntimeError("a buffer of " + std::to_string(bytes) + " bytes does not fit the device's maximum "
                         "allocation of " + std::to_string(maxAlloc) + " bytes; use a smaller image or scene");
  stats = RenderStats{};
  stats.waveSize = wave;

  StageInputs inputs;
  inputs.frame = frame;
  inputs.bvh = &bvh;
  inputs.materials = deviceMaterials(scene.materials);
  inputs.emitters = emitters.emitters;
  inputs.wave = wave;
  inputs.direct = direct;
  inputs.aovs = m.options.aovs;
  run.setup(inputs);

  if (m.options.verbose)
    std::cerr << "montecl: wave of " << wave << " pixel samples (" << (wave * bytesPerItem(slots, direct, m.options.aovs) >> 20)
              << " MiB), " << (total + wave - 1) / wave << " waves"
              << (direct ? ", " + std::to_string(emitters.emitters.size()) + " emitter triangles" : std::string())
              << "\n";

  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const auto mustStop = [&] {
    return (m.options.interrupt && *m.options.interrupt) ||
           (m.options.timeLimit > 0.0 && elapsed() >= m.options.timeLimit);
  };
  // Runs the active list's samples [sampleBase, sampleBase + spp) in waves; false if stopped early.
  std::uint64_t activeCount = pixels, expected = total;
  const auto runSamples = [&](std::uint64_t sampleBase, std::uint64_t spp) {
    const std::uint64_t first = sampleBase * activeCount, count = spp * activeCount;
    for (std::uint64_t done = 0; done < count;) {
      const std::uint32_t n = std::uint32_t(std::min(wave, count - done));
      run.beginWave(first + done, n);
      run.launch(Stage::generate, n);
      run.launch(Stage::intersect, n);
      if (direct) {
        run.launch(Stage::shade_direct, n);
        run.launch(Stage::intersect, n, RayInput::Bounce);
        run.launch(Stage::shade_direct_hit, n);
      } else {
        run.launch(Stage::shade_ao, n);
      }
      run.launch(Stage::intersect_shadow, std::uint64_t(n) * slots);
      const std::uint64_t touched = std::min<std::uint64_t>(n, activeCount);  // pixels in the wave
      run.launch(Stage::accumulate, touched);
      if (m.options.aovs) {
        run.launch(Stage::record_aov, n);
        run.launch(Stage::accumulate_aov, touched);
      }
      const std::uint32_t shadowCount = run.finishWave();

      done += n;
      stats.waves++;
      stats.samples += n;
      stats.cameraRays += n;
      stats.shadowRays += shadowCount;
      if (direct && scene.render.directSampling != DirectSampling::Light) stats.cameraRays += n;  // BRDF rays
      stats.seconds = elapsed();
      if (progress) progress(stats.samples, std::max(expected, stats.samples), stats);
      if (done < count && mustStop()) return false;
    }
    return !mustStop();
  };

  Film film;
  film.width = int(frame.width);
  film.height = int(frame.height);
  const std::uint64_t base = m.options.firstSample;
  if (m.options.targetError <= 0.0) {
    stats.rounds = 1;
    stats.stoppedEarly = !runSamples(base, std::uint64_t(scene.render.spp)) && stats.samples < total;
  } else {
    // Adaptive: all pixels share a sample count n while active, so the active list's items map to
    // sample indices n .. n + k - 1 of each pixel; the rounds are deterministic.
    std::uint64_t n = std::uint64_t(m.options.minSpp);
    const std::uint64_t maxSpp = m.options.minSpp <= m.options.maxSpp ? std::uint64_t(m.options.maxSpp) : throw std::invalid_argument("minSpp > maxSpp");
    expected = pixels * n;
    bool going = runSamples(base, n);
    stats.rounds = 1;
    std::vector<std::uint32_t> active;
    while (going && n < maxSpp) {
      run.readFilm(film);
      active.clear();
      for (std::uint32_t p = 0; p < pixels; ++p)
        if (film.mean[p].w == float(n) && relativeStandardError(film, p, m.options.errorFloor) > m.options.targetError)
          active.push_back(p);
      if (active.empty()) break;
      const std::uint64_t k = std::min(n, maxSpp - n);
      activeCount = active.size();
      expected = stats.samples + activeCount * k;
      run.setActivePixels(active);
      going = runSamples(base + n, k);
      n += k;
      stats.rounds++;
    }
    stats.stoppedEarly = !going;
  }
  run.readFilm(film);
  if (m.options.targetError > 0.0)
    for (std::uint64_t p = 0; p < pixels; ++p)
      stats.converged += relativeStandardError(film, p, m.options.errorFloor) <= m.options.targetError;
  stats.seconds = elapsed();
  return film;
}

double relativeStandardError(const Film& film, std::size_t p, double errorFloor) {
  const double n = film.mean[p].w;
  if (n < 2.0) return INFINITY;
  const glm::dvec3 w(0.2126, 0.7152, 0.0722);
  // Luminance of each sample is a linear combination of its channels; its variance needs the
  // cross terms, which are not accumulated, so the channels' standard errors are combined as if
  // fully correlated (an upper bound): se(L) <= sum_c w_c se_c.
  double mean = 0.0, se = 0.0;
  for (int c = 0; c < 3; ++c) {
    mean += w[c] * film.mean[p][c];
    se += w[c] * std::sqrt(film.variance(p, c) / n);
  }
  return se / std::max(mean, errorFloor);
}

}  // namespace montecl
