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

#include "kernels/stages/stage_common.h"
#include "render/stage_runner.h"
#include "render/device_materials.h"
#include "render/emitters.h"
#include "render/light_table.h"
#include "render/environment_table.h"
#include "render/frame_params.h"
#include "render/memory_check.h"
#include "render/triangle_shading.h"
#include "render/integrators.h"
#include "render/path_waves.h"
#include "render/sample_schedule.h"
#include "scene/camera_basis.h"
#include "util/errors.h"
#include "util/heap_trim.h"

namespace montecl {

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

bool WavefrontRenderer::programFromCache() const { return impl_->runner->programFromCache(); }
double WavefrontRenderer::programBuildMs() const { return impl_->runner->programBuildMs(); }

namespace {

void checkFits(std::uint64_t bytes, std::uint64_t maxAlloc, const char* remedy) {
  if (bytes > maxAlloc)
    throw RuntimeError("a buffer of " + std::to_string(bytes) + " bytes does not fit the device's maximum "
                       "allocation of " + std::to_string(maxAlloc) + " bytes; " + remedy);
}

// The wave cap: RenderOptions::maxWaveItems (by device), the memory budget, the device's largest
// allocation and 32-bit item indices (the planner sizes each wave under it).
std::uint64_t waveCap(const RenderOptions& o, const DeviceInfo& device, std::uint64_t maxAlloc,
                      const WaveShape& shape, std::uint64_t total) {
  std::uint64_t wave = o.waveSize;
  if (wave == 0) {
    const std::uint64_t cap = o.maxWaveItems ? o.maxWaveItems : defaultMaxWaveItems(device, shape.path);
    wave = std::max<std::uint64_t>(1, std::min(cap, o.memoryBudget / waveBytesPerItem(shape)));
  }
  wave = std::min<std::uint64_t>(wave, maxAlloc / (shape.slots * sizeof(ShadowWork)));
  wave = std::min<std::uint64_t>(wave, 0xffffffffull / shape.slots);
  return std::max<std::uint64_t>(1, std::min(wave, total));
}

// Everything the render uploads, built from the scene once: the frame constants (camera,
// settings, offsets, lights, textures), the device tables, and the wave's shape.
struct Prepared {
  StageInputs inputs;
  SceneTextures ownTextures;  // when the caller passed none and the scene names textures
  std::size_t emitterCount = 0;
};

void prepare(Prepared& p, const Scene& scene, const Bvh& bvh, const RenderOptions& o, const RenderPart& part,
             const DeviceInfo& device, StageRunner& run) {
  const IntegratorDesc& integrator = integratorDesc(scene.render.integrator);
  // Scene files are checked at load; a camera set in code is checked here (never NaN camera rays).
  const CameraProblem cameraProblem = cameraBasisProblem(scene.camera);
  if (!cameraProblem.empty()) throwInputError(scene.path, cameraProblem.key, cameraProblem.problem);
  const std::uint64_t pixels = std::uint64_t(scene.camera.width) * std::uint64_t(scene.camera.height);
  const std::uint64_t maxAlloc = run.maxAllocBytes();
  // The binary layout has no two-level traversal: the caller picks wide for instanced scenes.
  if (!bvh.instances.empty() && run.bvhLayout() == BvhLayout::Binary)
    throwInputError(scene.path, "--bvh-layout", "binary has no two-level form for the scene's instances; use wide");
  WaveShape shape = waveShapeFor(scene, 1, o.aovs);
  shape.instances = !bvh.instances.empty();
  shape.items = waveCap(o, device, maxAlloc, shape, pixels * std::uint64_t(scene.render.spp));
  checkImageMemory(device, scene.path, scene.camera.width, scene.camera.height, o.aovs,
                   shape.items * waveBytesPerItem(shape), shape.splits);

  StageInputs& in = p.inputs;
  PreparedTriangles own;
  if (!part.triangles) own = prepareTriangles(scene, bvh);
  PreparedTriangles& triangles = part.triangles ? *part.triangles : own;
  EnvironmentTable environment = buildEnvironment(scene);  // read (and checked) for any integrator
  for (std::uint64_t bytes : {pixels * sizeof(float4), std::uint64_t(bvhNodeBytes(bvh, run.bvhLayout())),
                              bvh.triangles.size() * sizeof(Triangle), environment.map.size() * sizeof(float4),
                              environment.cdf.size() * sizeof(float)})
    checkFits(bytes, maxAlloc, "use a smaller image or scene");
  if (part.keepTriangles && part.triangles) {
    in.shading = triangles.shading;
    in.vertexColors = triangles.vertexColors;
    in.tangents = triangles.tangents;
  } else {
    in.shading = std::move(triangles.shading);
    in.vertexColors = std::move(triangles.vertexColors);
    in.tangents = std::move(triangles.tangents);
  }
  checkFits(in.vertexColors.size() * sizeof(float4), maxAlloc, "use a smaller scene");
  checkFits(in.tangents.size() * sizeof(float4), maxAlloc, "use a smaller scene");
  checkFits(in.shading.size() * sizeof(TriangleShading), maxAlloc, "use a smaller scene");

  // Textures: the caller's (loaded under its budget, warnings shown), else loaded here.
  const SceneTextures* textures = part.textures;
  if (!textures && sceneHasTextures(scene)) {
    std::vector<std::string> ignored;
    p.ownTextures = loadSceneTextures(scene, defaultTextureBudget(device), ignored);
    textures = &p.ownTextures;
  }
  if (textures && textures->bytes() > maxAlloc)
    throw RuntimeError("textures of " + std::to_string(textures->bytes()) + " bytes do not fit the device's maximum "
                       "allocation of " + std::to_string(maxAlloc) + " bytes; lower --texture-budget");

  in.materials = deviceMaterials(scene.materials);
  if (textures) setTextureIndices(in.materials, *textures);
  // Textured emitters are weighted by their mean emission (written into in.shading for the pdfs).
  EmissionTextures emission;
  emission.materials = &in.materials;
  emission.shading = &in.shading;
  bool emissionTextured = false;
  for (const Material& m : in.materials) emissionTextured |= as_uint(m.maps.x) != MCL_NO_TEXTURE;
  if (emissionTextured)
    emission.tables = make_texture_tables(textures->textures.data(), textures->levels.data(), textures->texels.data());
  const EmitterTable emitters =
      integrator.lit ? buildEmitterTable(bvh, scene.materials, emissionTextured ? &emission : nullptr) : EmitterTable{};

  FrameExtras extras;
  // An emitter that is stochastically transparent: its light samples are weighted by its coverage
  // (light_area.h), which the packet stages' emitter sampling leaves to the scalar code as it does
  // textured emission.
  bool blendEmitter = false;
  for (const MaterialDesc& m : scene.materials)
    blendEmitter |= m.alphaBlend && m.emission != glm::vec3(0.0f) &&
                    materialAlphaTested(scene.materials, textures, std::size_t(&m - scene.materials.data()));
  extras.emissionTextured = (emissionTextured || blendEmitter) && integrator.lit;
  extras.shadowSlots = std::uint32_t(shape.slots);
  extras.offsetScale = triangles.offsetScale;
  extras.emitterCount = uint(emitters.emitters.size());
  extras.emitterPower = emitters.totalPower;
  if (integrator.lit) {  // otherwise the background only
    extras.environment = environment.radiance;
    extras.envWidth = environment.width;
    extras.envHeight = environment.height;
  }
  extras.envRotateY = environment.rotateY;
  extras.textureCount = textures ? std::uint32_t(textures->textures.size()) : 0u;
  // The triangles whose hits the traversals alpha-test, flagged (cut-outs, stochastic transparency).
  in.triangles = alphaFlaggedTriangles(bvh.triangles, scene.materials, textures);
  extras.alphaTested = !in.triangles.empty();
  extras.instanceCount = std::uint32_t(bvh.instances.size());
  extras.recordAovs = o.aovs;
  extras.countLanes = o.profile;
  // Incoherent rays in packets too (BRDF and path rays, AO and shadow queries) in a small tree.
  extras.packetAllRays = run.bvhLayout() == BvhLayout::Wide && packetTraversalForAllRays(bvh.wideNodes().size());
  LightTable lights = buildLightTable(scene, emitters.totalPower, environment, integrator.lit);
  extras.lights = lights.selection;
  const FrameParams frame = makeFrameParams(scene.camera, scene.render, extras);
  in.frame = frame;
  in.bvh = &bvh;
  if (textures) in.textures = textures;
  in.emitters = emitters.emitters;
  p.emitterCount = emitters.emitters.size();
  in.envMap = std::move(environment.map);
  in.envCdf = std::move(environment.cdf);
  in.lightRecords = std::move(lights.records);
  in.shape = shape;
  in.initialFilm = part.initialFilm;
}

// One render's wave loop: runs sample ranges of the active pixels in waves and books them.
class WaveLoop {
 public:
  WaveLoop(const RenderOptions& o, const RenderPart& part, StageRunner& run, const Scene& scene, const StageInputs& in,
           RenderStats& stats, const ProgressFn& progress)
      : o_(o), afterWave_(part.afterWave), run_(run), integrator_(integratorDesc(scene.render.integrator)), settings_(scene.render),
        frame_(in.frame), wave_(in.shape.items), stats_(stats), progress_(progress),
        // Wave sizes come from the planner unless a fixed --wave-size is asked for without a time limit.
        planned_(o.waveSize == 0 || o.timeLimit > 0.0),
        // Ahead: each wave is queued before the host waits for the one before it (StageRunner::
        // submitWave / waitWave), so the device does not idle while the host books a wave. Not with a
        // time limit (each wave is sized from the time left when it starts), nor with afterWave (it
        // reads the film of the waves booked so far), nor when the host reads counts within a wave.
        ahead_(!integrator_.path && !(o.timeLimit > 0.0) && !part.afterWave),
        // Fused waves (kernels/stages/wave_fused.h) on devices that run packets; the host backend
        // and GPUs (W = 1) keep a launch per stage, where the shadow queue compacts across the wave.
        // Not with instances: the fused stages' packet bodies have no two-level traversal.
        fuse_(o.fuseWaves && integrator_.fusable && run.lanes() > 1 && in.frame.instanceCount == 0),
        start_(std::chrono::steady_clock::now()) {}

  bool planned() const { return planned_; }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  bool mustStop() const {
    return (o_.interrupt && *o_.interrupt) || (o_.timeLimit > 0.0 && elapsed() >= o_.timeLimit);
  }
  // Under a budget: the schedule's round targets, which a film read after a wave carries.
  void setRoundTargets(const std::vector<std::uint64_t>* targets) { roundTargets_ = targets; }
  // The active list has activeCount pixels; expected: the samples the whole render will have.
  // blockShift: the round's item order (kernels/stages/stage_common.h).
  void setActive(std::uint64_t activeCount, std::uint64_t expected, unsigned blockShift) {
    activeCount_ = activeCount;
    expected_ = expected;
    blockShift_ = blockShift;
  }

  // Runs the active list's samples [sampleBase, sampleBase + spp) in waves; false if stopped early.
  bool runSamples(std::uint64_t sampleBase, std::uint64_t spp) {
    const std::uint64_t first = sampleBase * activeCount_, count = spp * activeCount_;
    waiting_ = 0;
    lastBooked_ = elapsed();
    for (std::uint64_t done = 0; done < count;) {
      std::uint64_t size = std::min(wave_, count - done);
      if (planned_) {
        const double timeLeft = o_.timeLimit > 0.0 ? o_.timeLimit - elapsed() : INFINITY;
        size = planWave(o_.planner, wave_, count - done, rate_, timeLeft);
        if (size == 0) return false;  // the time limit is (about) reached (never ahead: none queued)
        // Whole blocks, so that every wave starts a pixel's block and packets stay one pixel's.
        const std::uint64_t block = std::uint64_t(1) << blockShift_;
        if (size > block) size -= size % block;
      }
      const std::uint32_t n = std::uint32_t(size);
      queued_[waiting_++] = Queued{n, elapsed()};
      run_.beginWave(first + done, n);
      PathWaveCounts pathCounts;
      // One fused launch when the wave starts a block and holds at most one run per pixel: each
      // work item then owns its pixels' whole runs (wave_fused.h); groups of W blocks.
      const std::uint64_t block = std::uint64_t(1) << blockShift_, runs = (n + block - 1) / block;
      if (fuse_ && !integrator_.path && (first + done) % block == 0 && runs <= activeCount_) {
        const std::uint64_t group = std::uint64_t(run_.lanes()) << blockShift_;
        run_.launch(integrator_.fused, (n + group - 1) / group);  // AOVs too (FrameParams::recordAovs)
      } else {
        if (!(fuse_ && integrator_.path)) run_.launch(Stage::generate, n);
        integrator_.launchWave(run_, n, frame_.shadowSlots, o_.aovs, fuse_, pathCounts);
        const std::uint64_t touched = wave_touched_pixels(first + done, n, blockShift_, uint(activeCount_));
        run_.launch(Stage::accumulate, touched);
        if (o_.aovs) run_.launch(Stage::accumulate_aov, touched);
      }
      run_.submitWave();
      done += n;
      if (!ahead_ || waiting_ == 2) book(pathCounts);  // (ahead: never path, so no path counts)
      if (done < count && mustStop()) break;
    }
    while (waiting_ > 0) book(PathWaveCounts{});
    return !mustStop();
  }

 private:
  // Waits for the oldest queued wave and books it: statistics, rate, progress, afterWave.
  void book(const PathWaveCounts& pathCounts) {
    const Queued w = queued_[0];
    queued_[0] = queued_[1];
    --waiting_;
    const WaveCounts counts = run_.waitWave();
    const std::uint32_t n = w.n;
    RenderStats& s = stats_;
    s.waves++;
    s.samples += n;
    s.cameraRays += n + std::uint64_t(n) * integrator_.extraRays(settings_) + pathCounts.bounceRays;
    s.shadowRays += integrator_.path ? pathCounts.shadowRays : counts.shadowRays;
    if (s.pathSurvivors.size() < pathCounts.survivors.size()) s.pathSurvivors.resize(pathCounts.survivors.size(), 0);
    for (std::size_t b = 0; b < pathCounts.survivors.size(); ++b) s.pathSurvivors[b] += pathCounts.survivors[b];
    s.nanRays += counts.nanRays;
    s.seconds = elapsed();
    // The wave ran from its start, or (queued ahead) from the end of the one before it.
    const double from = std::max(w.start, lastBooked_);
    if (s.seconds > from) rate_ = double(n) / (s.seconds - from);
    lastBooked_ = s.seconds;
    if (progress_) progress_(s.samples, std::max(expected_, s.samples), s);
    if (afterWave_) afterWave_([&] {
      Film f;
      f.width = int(frame_.width);
      f.height = int(frame_.height);
      run_.readFilm(f);
      if (roundTargets_) f.roundTarget = *roundTargets_;
      return f;
    });
  }

  struct Queued {
    std::uint32_t n;
    double start;
  };
  const RenderOptions& o_;
  const std::function<void(const std::function<Film()>&)>& afterWave_;
  StageRunner& run_;
  const IntegratorDesc& integrator_;
  const RenderSettings& settings_;
  const FrameParams frame_;
  const std::uint64_t wave_;
  RenderStats& stats_;
  const ProgressFn& progress_;
  const bool planned_, ahead_, fuse_;
  const std::chrono::steady_clock::time_point start_;
  double rate_ = 0.0;  // pixel samples per second of the last wave (0: none yet)
  double lastBooked_ = 0.0;
  std::uint64_t activeCount_ = 0, expected_ = 0;
  unsigned blockShift_ = 0;
  const std::vector<std::uint64_t>* roundTargets_ = nullptr;
  Queued queued_[2] = {};
  int waiting_ = 0;
};

}  // namespace

Film WavefrontRenderer::render(const Scene& scene, const Bvh& bvh, RenderStats& stats,
                               const ProgressFn& progress, const RenderPart& part) {
  Impl& m = *impl_;
  StageRunner& run = *m.runner;
  Prepared prepared;
  prepare(prepared, scene, bvh, m.options, part, m.device, run);
  const StageInputs& inputs = prepared.inputs;
  const FrameParams& frame = inputs.frame;
  const std::uint64_t wave = inputs.shape.items, itemBytes = waveBytesPerItem(inputs.shape);
  const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
  const std::uint64_t total = pixels * std::uint64_t(scene.render.spp);
  stats = RenderStats{};
  stats.waveSize = wave;
  run.setProfile(m.options.profile ? &stats.profile : nullptr);
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

  WaveLoop loop(m.options, part, run, scene, inputs, stats, progress);
  if (m.options.wavesStart) m.options.wavesStart();
  if (m.options.verbose)
    std::cerr << "montecl: waves of up to " << wave << " pixel samples (" << (wave * itemBytes >> 20)
              << " MiB), " << (loop.planned() ? "sized from the measured rate" : std::to_string((total + wave - 1) / wave) + " waves")
              << (integratorDesc(scene.render.integrator).lit
                      ? ", " + std::to_string(prepared.emitterCount) + " emitter triangles"
                      : std::string())
              << "\n";
  Film film;
  film.width = int(frame.width);
  film.height = int(frame.height);
  if (part.initialFilm) film = *part.initialFilm;
  // Rounds of samples, each for the pixels at the lowest count (sample_schedule.h).
  const bool budget = scene.render.adaptive;
  SampleSchedule schedule(m.options, part, pixels, scene.render.spp, budget, sobolSplitsUsed(scene.render));
  if (budget) loop.setRoundTargets(&schedule.roundTargets());
  bool going = true, filmCurrent = true;  // film: the initial state (or unused: all counts 0)
  std::vector<std::uint32_t> active;
  std::uint64_t from = 0, to = 0, remaining = 0;
  while (going) {
    if (schedule.needsFilm() && !filmCurrent) run.readFilm(film);
    filmCurrent = false;
    if (!schedule.next(film, active, from, to, remaining)) break;
    const std::uint64_t sampleBase = m.options.firstSample + from;
    // Blocks of up to W samples per pixel: a packet's items are then one pixel's samples. Not under
    // a time limit: there every pixel gets a sample before any gets a second (even a short limit
    // leaves no pixel empty, and counts differ by at most one).
    const unsigned blockShift =
        m.options.timeLimit > 0.0 ? 0u : sample_block_shift(run.lanes(), sampleBase, to - from);
    loop.setActive(active.size(), stats.samples + remaining, blockShift);
    run.setActivePixels(active, blockShift);
    going = loop.runSamples(sampleBase, to - from);
    schedule.done(active, to);
    stats.rounds++;
  }
  std::vector<std::uint32_t>().swap(active);
  schedule.releaseTargets();
  run.finish(film);  // the film, and every buffer released (the film's part by part)
  if (budget) film.roundTarget = schedule.roundTargets();
  film.correlated = scene.render.sampler == Sampler::Sobol;
  settle.done = true;
  if (!going) stats.stoppedEarly = schedule.unfinished(film);
  if (m.options.targetError > 0.0)
    for (std::uint64_t p = 0; p < pixels; ++p)
      stats.converged += relativeStandardError(film, p, m.options.errorFloor) <= m.options.targetError;
  stats.seconds = loop.elapsed();
  run.setProfile(nullptr);
  if (m.options.verbose && !stats.pathSurvivors.empty())
    std::cerr << "montecl: " << survivorsSummary(stats.pathSurvivors) << "\n";
  return film;
}

PreparedTriangles prepareTriangles(const Scene& scene, const Bvh& bvh) {
  PreparedTriangles t;
  t.shading = buildTriangleShading(scene.triangles, bvh);
  t.vertexColors = buildVertexColors(scene, bvh);
  t.tangents = buildVertexTangents(scene, bvh);
  t.offsetScale = offsetScaleForScene(scene);
  return t;
}

std::uint64_t defaultTextureBudget(const DeviceInfo& device) {
  return device.isHost ? kDefaultTextureBudget : std::min(kDefaultTextureBudget, device.maxAllocBytes);
}

std::uint64_t defaultMaxWaveItems(const DeviceInfo& device, bool path) {
  if (device.isGpu && !device.isHost) return 1ull << 20;
  // Path tracing: four times that, since each bounce costs four launches and a read-back of the
  // next bounce's count, and after the Russian roulette depth few paths are left per launch.
  const std::uint64_t cap = std::max<std::uint64_t>(16384, 8192ull * std::max<std::uint32_t>(1, device.computeUnits));
  return path ? 4 * cap : cap;
}

}  // namespace montecl
