// wavefront.cpp: the render loop, one for every backend (render/stage_runner.h: OpenCL kernels or
// the host's C++ loops). Sizes the wave, uploads once, then per wave: reset the queue counters,
// generate -> intersect -> shade_ao | (shade_direct -> intersect bounce -> shade_direct_hit) ->
// intersect_shadow -> accumulate; the host never reads a queue count back to size a launch, except
// in path tracing's bounce loop (render/path_waves.cpp: generate -> bounces -> accumulate). Where
// nothing needs a wave booked before the next starts, the next wave is queued first (`ahead`).
#include "render/wavefront.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

#include "kernels/shared/microfacet.h"
#include "render/stage_runner.h"
#include "render/emitters.h"
#include "render/environment_table.h"
#include "render/frame_params.h"
#include "render/memory_check.h"
#include "render/triangle_shading.h"
#include "render/path_waves.h"
#include "scene/camera_basis.h"
#include "util/errors.h"
#include "util/heap_trim.h"

namespace montecl {
namespace {

// Bytes of per-wave buffers for one pixel sample with `slots` occlusion queries.
// Path tracing adds the path state: throughput, the next bounce's ray and the two id queues.
std::uint64_t bytesPerItem(std::uint32_t slots, bool bounce, bool aovs, bool path = false) {
  return sizeof(Ray) + sizeof(Hit) + sizeof(float4) + slots * (sizeof(float4) + sizeof(ShadowWork)) +
         (bounce ? sizeof(Ray) + sizeof(Hit) : 0) + (aovs ? 2 * sizeof(float4) : 0) +
         (path ? sizeof(float4) + sizeof(Ray) + 2 * sizeof(uint) : 0);
}

}  // namespace

struct WavefrontRenderer::Impl {
  Impl(const DeviceInfo& device, const RenderOptions& opts)
      : options(opts), device(device), runner(makeStageRunner(device, opts.workGroupSize, opts.bvhLayout, opts.profile, opts.lanes)) {}
  RenderOptions options;
  DeviceInfo device;
  std::unique_ptr<StageRunner> runner;
};

WavefrontRenderer::WavefrontRenderer(const DeviceInfo& device, const RenderOptions& options)
    : impl_(std::make_unique<Impl>(device, options)) {}

WavefrontRenderer::~WavefrontRenderer() = default;

void WavefrontRenderer::setTextures(const SceneTextures* textures) { impl_->options.textures = textures; }

bool WavefrontRenderer::programFromCache() const { return impl_->runner->programFromCache(); }
double WavefrontRenderer::programBuildMs() const { return impl_->runner->programBuildMs(); }

namespace {

std::vector<Material> deviceMaterials(const std::vector<MaterialDesc>& materials) {
  std::vector<Material> out;
  const float noTexture = glm::uintBitsToFloat(MCL_NO_TEXTURE);
  for (const MaterialDesc& m : materials) {
    Material d{};
    d.albedo = glm::vec4(m.albedo, noTexture);
    d.emission = glm::vec4(m.emission, m.twoSidedEmission ? 1.0f : 0.0f);
    d.specular = glm::vec4(m.specular, ggx_alpha_from_ns(m.specularExponent));
    d.alpha = glm::vec4(noTexture, m.alphaCutoff, glm::uintBitsToFloat(0u), 0.0f);
    out.push_back(d);
  }
  return out;
}

}  // namespace

Film WavefrontRenderer::render(const Scene& scene, const Bvh& bvh, RenderStats& stats,
                               const ProgressFn& progress) {
  Impl& m = *impl_;
  StageRunner& run = *m.runner;
  const bool direct = scene.render.integrator == Integrator::Direct;
  const bool path = scene.render.integrator == Integrator::Path;
  const std::uint32_t slots = direct ? std::uint32_t(scene.render.lightSamples) + 1
                              : path ? std::uint32_t(scene.render.lightSamples)
                                     : 1;
  // Scene files are checked at load; a camera set in code is checked here (never NaN camera rays).
  const CameraProblem cameraProblem = cameraBasisProblem(scene.camera);
  if (!cameraProblem.empty()) throwInputError(scene.path, cameraProblem.key, cameraProblem.problem);
  FrameParams frame = makeFrameParams(scene.camera, scene.render, slots);
  frame.offsetScale = offsetScaleFor(scene.triangles);
  const EmitterTable emitters = direct || path ? buildEmitterTable(bvh, scene.materials) : EmitterTable{};
  frame.emitterCount = uint(emitters.emitters.size());
  frame.emitterPower = emitters.totalPower;
  EnvironmentTable environment = buildEnvironment(scene, frame);  // read (and checked) for any integrator
  if (!direct && !path) frame.environment = float4(0.0f), frame.envWidth = frame.envHeight = 0;  // AO: background only
  const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
  const std::uint64_t total = pixels * std::uint64_t(scene.render.spp);

  // Wave cap: RenderOptions::maxWaveItems (by device), the memory budget, the device's largest
  // allocation, and 32-bit item indices. The planner sizes each wave under it.
  const std::uint64_t maxAlloc = run.maxAllocBytes();
  std::uint64_t wave = m.options.waveSize;
  const std::uint64_t itemBytes = bytesPerItem(slots, direct, m.options.aovs, path);
  if (wave == 0) {
    const std::uint64_t cap = m.options.maxWaveItems ? m.options.maxWaveItems : defaultMaxWaveItems(m.device);
    wave = std::max<std::uint64_t>(1, std::min(cap, m.options.memoryBudget / itemBytes));
  }
  wave = std::min<std::uint64_t>(wave, maxAlloc / (slots * sizeof(ShadowWork)));
  wave = std::min<std::uint64_t>(wave, 0xffffffffull / slots);
  wave = std::max<std::uint64_t>(1, std::min(wave, total));
  checkImageMemory(m.device, scene.path, scene.camera.width, scene.camera.height, m.options.aovs,
                   wave * itemBytes);
  for (std::uint64_t bytes : {pixels * sizeof(float4), std::uint64_t(bvhNodeBytes(bvh, run.bvhLayout())),
                              bvh.triangles.size() * sizeof(Triangle), environment.map.size() * sizeof(float4),
                              environment.cdf.size() * sizeof(float)})
    if (bytes > maxAlloc)
      throw RuntimeError("a buffer of " + std::to_string(bytes) + " bytes does not fit the device's maximum "
                         "allocation of " + std::to_string(maxAlloc) + " bytes; use a smaller image or scene");
  std::vector<TriangleShading> shading = buildTriangleShading(scene.triangles, bvh);
  if (shading.size() * sizeof(TriangleShading) > maxAlloc)
    throw RuntimeError("a buffer of " + std::to_string(shading.size() * sizeof(TriangleShading)) +
                       " bytes does not fit the device's maximum allocation of " + std::to_string(maxAlloc) +
                       " bytes; use a smaller scene");
  stats = RenderStats{};
  stats.waveSize = wave;
  run.setProfile(m.options.profile ? &stats.profile : nullptr);

  // Textures: the caller's (loaded under its budget, warnings shown), else loaded here.
  SceneTextures ownTextures;
  const SceneTextures* textures = m.options.textures;
  if (!textures && sceneHasTextures(scene)) {
    std::vector<std::string> ignored;
    ownTextures = loadSceneTextures(scene, std::min<std::uint64_t>(kDefaultTextureBudget, maxAlloc), ignored);
    textures = &ownTextures;
  }
  if (textures && textures->bytes() > maxAlloc)
    throw RuntimeError("textures of " + std::to_string(textures->bytes()) + " bytes do not fit the device's maximum "
                       "allocation of " + std::to_string(maxAlloc) + " bytes; lower --texture-budget");
  frame.textureCount = textures ? std::uint32_t(textures->textures.size()) : 0u;
  StageInputs inputs;
  inputs.frame = frame;
  inputs.bvh = &bvh;
  inputs.shading = std::move(shading);
  inputs.materials = deviceMaterials(scene.materials);
  if (textures) {
    setTextureIndices(inputs.materials, *textures);
    inputs.textures = textures;
    inputs.triangles = alphaFlaggedTriangles(bvh.triangles, *textures);
  }
  inputs.emitters = emitters.emitters;
  inputs.envMap = std::move(environment.map);
  inputs.envCdf = std::move(environment.cdf);
  inputs.wave = wave;
  inputs.direct = direct;
  inputs.path = path;
  inputs.aovs = m.options.aovs;
  inputs.initialFilm = m.options.initialFilm;
  if (m.options.trianglesRead) m.options.trianglesRead(), trimHeap();  // scene.triangles: not read below
  run.setup(inputs);
  // Buffers may use inputs' arrays in place: if anything below throws, the queue is settled and
  // the buffers released before inputs goes (StageRunner::abandon).
  struct Settle {
    StageRunner& run;
    bool done = false;
    ~Settle() {
      if (!done) run.abandon();
    }
  } settle{run};

  // Wave sizes come from the planner unless a fixed --wave-size is asked for without a time limit.
  const bool planned = m.options.waveSize == 0 || m.options.timeLimit > 0.0;
  double rate = 0.0;  // pixel samples per second of the last wave (0: none yet)
  if (m.options.verbose)
    std::cerr << "montecl: waves of up to " << wave << " pixel samples (" << (wave * itemBytes >> 20)
              << " MiB), " << (planned ? "sized from the measured rate" : std::to_string((total + wave - 1) / wave) + " waves")
              << (direct || path ? ", " + std::to_string(emitters.emitters.size()) + " emitter triangles" : std::string())
              << "\n";

  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const auto mustStop = [&] {
    return (m.options.interrupt && *m.options.interrupt) ||
           (m.options.timeLimit > 0.0 && elapsed() >= m.options.timeLimit);
  };
  // Runs the active list's samples [sampleBase, sampleBase + spp) in waves; false if stopped early.
  std::uint64_t activeCount = pixels, expected = total;
  // Ahead: each wave is queued before the host waits for the one before it (StageRunner::
  // submitWave / waitWave), so the device does not idle while the host books a wave. Not with a
  // time limit (each wave is sized from the time left when it starts), nor with afterWave (it
  // reads the film of the waves booked so far), nor for path tracing (its bounces wait anyway).
  const bool ahead = !path && !(m.options.timeLimit > 0.0) && !m.options.afterWave;
  const auto runSamples = [&](std::uint64_t sampleBase, std::uint64_t spp) {
    const std::uint64_t first = sampleBase * activeCount, count = spp * activeCount;
    struct Queued {
      std::uint32_t n;
      double start;
    } queued[2];
    int waiting = 0;
    double lastBooked = elapsed();
    // Waits for the oldest queued wave and books it: statistics, rate, progress, afterWave.
    const auto book = [&](const PathWaveCounts& pathCounts) {
      const Queued w = queued[0];
      queued[0] = queued[1];
      --waiting;
      const WaveCounts counts = run.waitWave();
      const std::uint32_t n = w.n;
      stats.waves++;
      stats.samples += n;
      stats.cameraRays += n;
      stats.shadowRays += path ? pathCounts.shadowRays : counts.shadowRays;
      stats.cameraRays += pathCounts.bounceRays;
      auto& survivors = stats.pathSurvivors;
      if (survivors.size() < pathCounts.survivors.size()) survivors.resize(pathCounts.survivors.size(), 0);
      for (std::size_t b = 0; b < pathCounts.survivors.size(); ++b) survivors[b] += pathCounts.survivors[b];
      stats.nanRays += counts.nanRays;
      if (direct && scene.render.directSampling != DirectSampling::Light) stats.cameraRays += n;  // BRDF rays
      stats.seconds = elapsed();
      // The wave ran from its start, or (queued ahead) from the end of the one before it.
      const double from = std::max(w.start, lastBooked);
      if (stats.seconds > from) rate = double(n) / (stats.seconds - from);
      lastBooked = stats.seconds;
      if (progress) progress(stats.samples, std::max(expected, stats.samples), stats);
      if (m.options.afterWave) m.options.afterWave([&] {
        Film f;
        f.width = int(frame.width);
        f.height = int(frame.height);
        run.readFilm(f);
        return f;
      });
    };
    for (std::uint64_t done = 0; done < count;) {
      std::uint64_t size = std::min(wave, count - done);
      if (planned) {
        const double timeLeft = m.options.timeLimit > 0.0 ? m.options.timeLimit - elapsed() : INFINITY;
        size = planWave(m.options.planner, wave, count - done, rate, timeLeft);
        if (size == 0) return false;  // the time limit is (about) reached (never ahead: none queued)
      }
      const std::uint32_t n = std::uint32_t(size);
      queued[waiting++] = Queued{n, elapsed()};
      run.beginWave(first + done, n);
      run.launch(Stage::generate, n);
      PathWaveCounts pathCounts;
      if (path) {
        runPathWave(run, n, slots, m.options.aovs, pathCounts);  // (records the AOVs at bounce 0)
      } else {
        run.launch(Stage::intersect, n);
        if (direct) {
          run.launch(Stage::shade_direct, n);
          run.launch(Stage::intersect, n, RayInput::Bounce);
          run.launch(Stage::shade_direct_hit, n);
        } else {
          run.launch(Stage::shade_ao, n);
        }
        run.launch(Stage::intersect_shadow, std::uint64_t(n) * slots);
        if (m.options.aovs) run.launch(Stage::record_aov, n);
      }
      const std::uint64_t touched = std::min<std::uint64_t>(n, activeCount);  // pixels in the wave
      run.launch(Stage::accumulate, touched);
      if (m.options.aovs) run.launch(Stage::accumulate_aov, touched);
      run.submitWave();
      done += n;
      if (!ahead || waiting == 2) book(pathCounts);  // (ahead: never path, so no path counts)
      if (done < count && mustStop()) break;
    }
    while (waiting > 0) book(PathWaveCounts{});
    return !mustStop();
  };

  Film film;
  film.width = int(frame.width);
  film.height = int(frame.height);
  if (m.options.initialFilm) film = *m.options.initialFilm;
  std::vector<std::uint32_t> mine = m.options.pixels;
  if (mine.empty())
    for (std::uint64_t p = 0; p < pixels; ++p) mine.push_back(std::uint32_t(p));
  std::vector<std::uint64_t> counts(pixels, 0);
  if (m.options.initialFilm) counts = m.options.initialFilm->count;
  // Each pixel's schedule depends only on its own count and state: without adaptive sampling it
  // needs samples up to spp; with it, rounds end at minSpp, 2 minSpp, 4 minSpp ... maxSpp, and at
  // each round's end the pixel goes on while its relative error exceeds the target. nextTarget:
  // the count the pixel renders to next (0: done). A fresh render is one round (or the adaptive
  // rounds); a resumed film (pixels at different counts) first brings the lowest counts up.
  const bool adaptive = m.options.targetError > 0.0;
  const std::uint64_t minSpp = std::uint64_t(m.options.minSpp), maxSpp = std::uint64_t(m.options.maxSpp);
  if (adaptive && minSpp > maxSpp) throw std::invalid_argument("minSpp > maxSpp");
  const auto nextTarget = [&](std::uint32_t p) -> std::uint64_t {
    const std::uint64_t c = counts[p];
    if (!adaptive) return c < std::uint64_t(scene.render.spp) ? std::uint64_t(scene.render.spp) : 0;
    if (c < minSpp) return minSpp;
    std::uint64_t bound = minSpp;
    while (bound < c) bound = std::min(2 * bound, maxSpp);
    if (bound > c) return bound;  // within a round
    if (c >= maxSpp || relativeStandardError(film, p, m.options.errorFloor) <= m.options.targetError) return 0;
    return std::min(2 * c, maxSpp);
  };
  const std::uint64_t base = m.options.firstSample;
  bool going = true, filmCurrent = true;  // film: the initial state (or unused: all counts 0)
  std::vector<std::uint64_t> target(pixels, 0);
  std::vector<std::uint32_t> active;
  while (going) {
    if (adaptive && !filmCurrent) run.readFilm(film);
    filmCurrent = false;
    std::uint64_t low = UINT64_MAX, remaining = 0;
    for (std::uint32_t p : mine) {
      target[p] = nextTarget(p);
      if (target[p]) low = std::min(low, counts[p]), remaining += target[p] - counts[p];
    }
    if (low == UINT64_MAX) break;
    std::uint64_t upTo = UINT64_MAX;  // the lowest group's target, or the next count above it
    active.clear();
    for (std::uint32_t p : mine) {
      if (!target[p]) continue;
      if (counts[p] == low) active.push_back(p), upTo = std::min(upTo, target[p]);
      else upTo = std::min(upTo, counts[p]);
    }
    activeCount = active.size();
    expected = stats.samples + remaining;
    run.setActivePixels(active);
    going = runSamples(base + low, upTo - low);
    for (std::uint32_t p : active) counts[p] = upTo;
    stats.rounds++;
  }
  std::vector<std::uint64_t>().swap(target);
  std::vector<std::uint32_t>().swap(active);
  run.finish(film);  // the film, and every buffer released (the film's part by part)
  settle.done = true;
  if (!going) {  // stopped: was anything left?
    for (std::uint32_t p : mine) counts[p] = film.count[p];
    stats.stoppedEarly = std::any_of(mine.begin(), mine.end(), [&](std::uint32_t p) { return nextTarget(p) != 0; });
  }
  if (m.options.targetError > 0.0)
    for (std::uint64_t p = 0; p < pixels; ++p)
      stats.converged += relativeStandardError(film, p, m.options.errorFloor) <= m.options.targetError;
  stats.seconds = elapsed();
  run.setProfile(nullptr);
  if (m.options.verbose && path) std::cerr << "montecl: " << survivorsSummary(stats.pathSurvivors) << "\n";
  return film;
}

std::uint64_t defaultMaxWaveItems(const DeviceInfo& device) {
  if (device.isGpu && !device.isHost) return 1ull << 20;
  return std::max<std::uint64_t>(16384, 8192ull * std::max<std::uint32_t>(1, device.computeUnits));
}

double relativeStandardError(const Film& film, std::size_t p, double errorFloor) {
  const double n = double(film.count[p]);
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
