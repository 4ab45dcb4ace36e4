// cl_backend.cpp: the OpenCL backend of the wave loop: one StageProgram (context, in-order queue,
// the stage kernels built for the BVH layout), the per-render device buffers in ClBindings, and one
// kernel launch per stage with its arguments bound by name (render/stage_bindings.h). Queue
// counters are reset on the device; the host never reads a queue count back to size a launch
// (kernels return past the device-side count), only once per wave for the statistics. With a
// profile (setProfile), each launch keeps its event and waitWave adds the events' times.
// Memory: on CPU devices the BVH nodes and the read-only scene tables (triangles, shading, texels,
// ...: render/scene_tables.h) are used in place (CL_MEM_USE_HOST_PTR: no second copy); finish() reads the film one part at a
// time, releasing each part's buffer, so the film is never whole on both sides.
#include <algorithm>
#include <array>
#include <stdexcept>

#include "cl/device_tuning.h"
#include "render/scene_tables.h"
#include "render/stage_program.h"
#include "render/stage_runner.h"
#include "util/errors.h"
#include "util/heap_trim.h"

namespace montecl {
namespace {

class ClStageRunner final : public StageRunner {
 public:
  ClStageRunner(const DeviceInfo& device, std::size_t workGroupSize, BvhLayout layout, bool profiling,
                unsigned lanes)
      : program_(device, layout, workGroupSize, profiling, lanes), cl_(program_.session()),
        inPlace_(device.isCpu && !isOclgrind(device)) {
    for (int s = 0; s < kStageCount; ++s) kernels_[s] = cl_.kernel(stageName(Stage(s)));
  }

  std::uint64_t maxAllocBytes() const override { return cl_.device().maxAllocBytes; }
  BvhLayout bvhLayout() const override { return program_.layout(); }
  bool programFromCache() const override { return cl_.build().fromCache; }
  double programBuildMs() const override { return cl_.build().buildMs; }

  void setup(const StageInputs& in) override {
    const WaveShape shape = setupShape(in);
    shape_ = shape;
    pixels_ = shape.pixels;
    frame_ = in.frame;
    firstSubmitted_ = submittedCount_ = 0;
    aovs_ = shape.aovs;
    splits_ = shape.splits;
    ClBindings& b = bindings_;
    b.frame = {cl_.upload(std::vector<FrameParams>{in.frame})};
    const bool binary = program_.layout() == BvhLayout::Binary;
    b.nodes = {binary ? (in.bvh->nodes.empty() ? program_.uploadNodes(*in.bvh) : readOnly(in.bvh->nodes))
                      : readOnly(in.bvh->wideNodes())};
    tables_.view(in);
#define MCL_CL_TABLE(name, T, dummy) b.name = {readOnly(*tables_.name)};
    MCL_SCENE_TABLES(MCL_CL_TABLE)
#undef MCL_CL_TABLE
    std::vector<cl_uint> all(pixels_);
    for (std::uint64_t p = 0; p < pixels_; ++p) all[p] = cl_uint(p);
    b.active = {cl_.upload(all, CL_MEM_READ_WRITE)};
    // The wave buffers only the stages touch; counters and film the host writes and reads.
#define MCL_CL_ALLOC(name, T, per, need) b.name = {cl_.scratch<T>(bufferCount(Per::per, Need::need, shape))};
#define MCL_CL_COUNTER(name) b.name = {cl_.buffer<cl_uint>(1)};
#define MCL_CL_FILM(name, per, need) b.name = {cl_.buffer<cl_float4>(bufferCount(Per::per, Need::need, shape))};
    MCL_WAVE_BUFFERS(MCL_CL_ALLOC)
    MCL_WAVE_COUNTERS(MCL_CL_COUNTER)
    MCL_FILM_BUFFERS(MCL_CL_FILM)
#undef MCL_CL_ALLOC
#undef MCL_CL_COUNTER
#undef MCL_CL_FILM
    // Cleared by writes, not clEnqueueFillBuffer: Oclgrind's uninitialised-memory check does not
    // count a fill as initialising memory, and a write costs the same here. The zeros are written
    // from one block of at most 1 MiB (not a film-sized host array).
#define MCL_CL_FILM_BUFFER(name, per, need) &b.name.buffer,
    const cl::Buffer* films[] = {MCL_FILM_BUFFERS(MCL_CL_FILM_BUFFER)};
#undef MCL_CL_FILM_BUFFER
    const std::array<std::uint64_t, kFilmBufferCount> words = filmWords();
    bool loaded[kFilmBufferCount] = {};
    if (const Film* f = in.initialFilm) {
      // A resumed film: its parts by name, mean and meanLo as the device words (count bits in w).
      std::vector<glm::vec4> meanWords, meanLoWords;
      f->packCounts(meanWords, meanLoWords);
      const auto from = [&](const std::vector<glm::vec4>& part) -> const std::vector<glm::vec4>& {
        return &part == &f->mean ? meanWords : &part == &f->meanLo ? meanLoWords : part;
      };
#define MCL_CL_FILM_FROM(name, per, need) &from(f->name),
      const std::vector<glm::vec4>* parts[] = {MCL_FILM_BUFFERS(MCL_CL_FILM_FROM)};
#undef MCL_CL_FILM_FROM
      for (int i = 0; i < kFilmBufferCount; ++i)
        if (words[i] && parts[i]->size() >= words[i]) {
          cl_.queue().enqueueWriteBuffer(*films[i], CL_TRUE, 0, words[i] * sizeof(cl_float4), parts[i]->data());
          loaded[i] = true;
        }
    }
    // One write per part where it fits the block: Oclgrind resets a buffer's definedness only on a
    // write at offset 0 (cl_session.h scratch), so the AOV sums (two per pixel) must not come in two.
    const std::vector<cl_float4> zeros(std::min<std::uint64_t>(*std::max_element(words.begin(), words.end()), 65536),
                                       cl_float4{{0.0f, 0.0f, 0.0f, 0.0f}});
    for (int i = 0; i < kFilmBufferCount; ++i)
      for (std::uint64_t at = 0; !loaded[i] && at < words[i]; at += zeros.size())
        cl_.queue().enqueueWriteBuffer(*films[i], CL_FALSE, at * sizeof(cl_float4),
                                       std::min<std::uint64_t>(zeros.size(), words[i] - at) * sizeof(cl_float4),
                                       zeros.data());
    cl_.queue().finish();  // (zeros is about to go)
  }

  unsigned lanes() const override { return program_.lanes(); }

  void setActivePixels(const std::vector<std::uint32_t>& pixels, unsigned blockShift) override {
    frame_.activeCount = cl_uint(pixels.size());
    frame_.sampleBlockShift = blockShift;
    cl_.queue().enqueueWriteBuffer(bindings_.frame.buffer, CL_TRUE, 0, sizeof(FrameParams), &frame_);
    if (!pixels.empty())
      cl_.queue().enqueueWriteBuffer(bindings_.active.buffer, CL_TRUE, 0, pixels.size() * sizeof(cl_uint),
                                     pixels.data());
  }

  void beginWave(std::uint64_t waveStart, std::uint32_t count) override {
    bindings_.waveStart = waveStart;
    bindings_.waveCount = count;
    // Counters reset by (non-blocking) writes from members that outlive the wave; the ray count
    // from the slot of this wave (the other one may still be queued for the wave before).
    Submitted& w = submitted_[(firstSubmitted_ + submittedCount_) % 2];
    w.rayCount = count;
    cl_.queue().enqueueWriteBuffer(bindings_.rayCount.buffer, CL_FALSE, 0, sizeof(cl_uint), &w.rayCount);
    cl_.queue().enqueueWriteBuffer(bindings_.queueCount.buffer, CL_FALSE, 0, sizeof(cl_uint), &kZero);
    cl_.queue().enqueueWriteBuffer(bindings_.nanRays.buffer, CL_FALSE, 0, sizeof(cl_uint), &kZero);
    if (profile_) {
      cl_.queue().enqueueWriteBuffer(bindings_.packedLanes.buffer, CL_FALSE, 0, sizeof(cl_uint), &kZero);
      cl_.queue().enqueueWriteBuffer(bindings_.aloneLanes.buffer, CL_FALSE, 0, sizeof(cl_uint), &kZero);
    }
  }

  // Arguments are set at every launch (a handful of clSetKernelArg calls per stage and wave): the
  // kernel keeps them until its next launch, and the bounce launch of intersect binds other rays.
  void launch(Stage s, std::uint64_t items, RayInput rays) override {
    cl::Kernel& k = kernels_[int(s)];
    bindStageArgs(k, s, rays == RayInput::Camera ? bindings_ : bindings_.forRays(rays));
    // A packet stage's work item runs W consecutive items (kernels/shared/lanes.h).
    if (stageRunsPackets(s)) items = (items + program_.lanes() - 1) / program_.lanes();
    // A fused stage's work item is a whole group of W C items (kernels/stages/wave_fused.h), so a
    // wave has few of them: one per work-group, so that every compute unit gets a share.
    const std::size_t local = stageIsFused(s) ? 1 : 0;
    if (!profile_) return cl_.launch(k, items, nullptr, local);
    cl::Event event;
    cl_.launch(k, items, &event, local);
    if (event()) launched_.push_back({stageProfileName(s, rays), event});
  }

  void startBounce(std::uint32_t bounce) override {
    bindings_.pathBounce = bounce;
    cl_.queue().enqueueWriteBuffer(bindings_.queueCount.buffer, CL_FALSE, 0, sizeof(cl_uint), &kZero);
    cl_.queue().enqueueWriteBuffer(bindings_.nextCount.buffer, CL_FALSE, 0, sizeof(cl_uint), &kZero);
  }

  void endBounce() override {
    ClBindings& b = bindings_;
    std::swap(b.rays, b.nextRays);
    std::swap(b.pathIds, b.nextPathIds);
    std::swap(b.rayCount, b.nextCount);
  }

  BounceCounts readBounceCounts() override {
    cl_.queue().enqueueReadBuffer(bindings_.queueCount.buffer, CL_FALSE, 0, sizeof(cl_uint), &bounceCounts_[1]);
    cl_.queue().enqueueReadBuffer(bindings_.rayCount.buffer, CL_TRUE, 0, sizeof(cl_uint), &bounceCounts_[0]);
    return BounceCounts{bounceCounts_[0], bounceCounts_[1]};
  }

  void abandon() noexcept override {
    try {
      cl_.queue().finish();
    } catch (...) {  // (the queue is lost: nothing more runs on it)
    }
    releaseBuffersAndWaves();
  }

  void submitWave() override {
    if (submittedCount_ == 2) throw std::logic_error("submitWave: two waves are already waiting");
    Submitted& w = submitted_[(firstSubmitted_ + submittedCount_++) % 2];
    w.launched = std::move(launched_);
    launched_.clear();
    cl_.queue().enqueueReadBuffer(bindings_.nanRays.buffer, CL_FALSE, 0, sizeof(cl_uint), &w.counts[1]);
    w.lanes[0] = w.lanes[1] = 0;
    if (profile_) {
      cl_.queue().enqueueReadBuffer(bindings_.packedLanes.buffer, CL_FALSE, 0, sizeof(cl_uint), &w.lanes[0]);
      cl_.queue().enqueueReadBuffer(bindings_.aloneLanes.buffer, CL_FALSE, 0, sizeof(cl_uint), &w.lanes[1]);
    }
    cl_.queue().enqueueReadBuffer(bindings_.queueCount.buffer, CL_FALSE, 0, sizeof(cl_uint), &w.counts[0], nullptr,
                                  &w.read);
  }

  WaveCounts waitWave() override {
    Submitted& w = submitted_[firstSubmitted_];
    w.read.wait();  // the last command of the wave (in order): its launches are complete too
    for (auto& [name, event] : w.launched)
      if (profile_)
        profile_->add(name, double(event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                                   event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) * 1e-6);
    w.launched.clear();
    if (profile_) {
      profile_->packedLanes += w.lanes[0];
      profile_->aloneLanes += w.lanes[1];
    }
    firstSubmitted_ = (firstSubmitted_ + 1) % 2;
    --submittedCount_;
    return WaveCounts{w.counts[0], w.counts[1]};
  }

  void readFilm(Film& film) override {
    const std::pair<const ClArray<float4>*, std::vector<glm::vec4>*> parts[] = {
        {&bindings_.mean, &film.mean}, {&bindings_.meanLo, &film.meanLo}, {&bindings_.m2, &film.m2},
        {&bindings_.m2Lo, &film.m2Lo}};
    for (const auto& [device, host] : parts) {  // one wait, at the last read (in-order queue)
      host->resize(pixels_);
      const bool last = host == &film.m2Lo;
      cl_.queue().enqueueReadBuffer(device->buffer, last ? CL_TRUE : CL_FALSE, 0, pixels_ * sizeof(cl_float4),
                                    host->data());
    }
    film.unpackCounts();
    if (aovs_) {
      film.aovSum.resize(MCL_AOV_VECTORS * pixels_);
      cl_.queue().enqueueReadBuffer(bindings_.aovSum.buffer, CL_TRUE, 0, MCL_AOV_VECTORS * pixels_ * sizeof(cl_float4),
                                    film.aovSum.data());
    }
    film.split.resize(splits_ * pixels_);
    if (splits_)
      cl_.queue().enqueueReadBuffer(bindings_.split.buffer, CL_TRUE, 0, splits_ * pixels_ * sizeof(cl_float4),
                                    film.split.data());
  }

  // The last read: every buffer but the film's is released first (the scene's arrays may be used
  // in place and must not be referenced after render()), then each film part is read and its
  // buffer released before the next, so the film exists twice one part at a time only.
  void finish(Film& film) override {
    cl_.queue().finish();
    ClBindings& b = bindings_;
#define MCL_CL_FILM_PART(name, per, need) {b.name.buffer, &film.name},
    std::pair<cl::Buffer, std::vector<glm::vec4>*> parts[] = {MCL_FILM_BUFFERS(MCL_CL_FILM_PART)};
#undef MCL_CL_FILM_PART
    const std::array<std::uint64_t, kFilmBufferCount> words = filmWords();
    releaseBuffersAndWaves();
    trimHeap();
    for (int i = 0; i < kFilmBufferCount; ++i) {
      auto& [device, host] = parts[i];
      host->resize(words[i]);
      if (words[i])
        cl_.queue().enqueueReadBuffer(device, CL_TRUE, 0, words[i] * sizeof(cl_float4), host->data());
      device = cl::Buffer();
      trimHeap();
    }
    film.unpackCounts();
  }

 private:
  // Every buffer (the scene's in-place arrays included) and every queued wave's events let go:
  // after the queue has finished, by finish() and abandon().
  void releaseBuffersAndWaves() {
    bindings_ = ClBindings{};
    tables_.release();
    launched_.clear();
    for (Submitted& w : submitted_) w.launched.clear();
    firstSubmitted_ = submittedCount_ = 0;
  }

  // The words of each film part this render holds (MCL_FILM_BUFFERS order; 0: a dummy).
  std::array<std::uint64_t, kFilmBufferCount> filmWords() const {
    std::array<std::uint64_t, kFilmBufferCount> words{};
    int i = 0;
#define MCL_CL_FILM_WORDS(name, per, need) \
  words[i++] = needed(Need::need, shape_) ? bufferCount(Per::per, Need::need, shape_) : 0;
    MCL_FILM_BUFFERS(MCL_CL_FILM_WORDS)
#undef MCL_CL_FILM_WORDS
    return words;
  }

  // A read-only array the kernels read: used in place on CPU devices (the array must outlive the
  // buffer: finish() releases it), copied elsewhere (GPUs: device memory; Oclgrind).
  template <typename T>
  cl::Buffer readOnly(const std::vector<T>& data) const {
    if (!inPlace_ || data.empty()) return cl_.upload(data);
    return cl::Buffer(cl_.context(), CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, data.size() * sizeof(T),
                      const_cast<T*>(data.data()));
  }

  StageProgram program_;
  ClSession& cl_;
  bool inPlace_;
  std::array<cl::Kernel, kStageCount> kernels_;
  ClBindings bindings_;
  SceneTables tables_;  // what the scene tables' buffers use in place (CPU devices)
  WaveShape shape_;     // the render's buffer shape (setup)
  bool aovs_ = false;
  std::uint64_t splits_ = 0;  // sobol sub-sequences with film accumulators (Film::split)
  static constexpr cl_uint kZero = 0;  // what the counter resets write
  std::vector<std::pair<std::string, cl::Event>> launched_;  // this wave's launches (profiling)
  // A wave between beginWave and waitWave: its ray count as written, its counts as read, the read's
  // event and its launches (profiling). Two slots: the next wave is queued before the host waits.
  struct Submitted {
    cl_uint rayCount = 0;
    cl_uint counts[2] = {0, 0};  // occlusion queries, non-finite rays
    cl_uint lanes[2] = {0, 0};   // --profile: hits shaded in lane types, one by one
    cl::Event read;
    std::vector<std::pair<std::string, cl::Event>> launched;
  };
  Submitted submitted_[2];
  unsigned firstSubmitted_ = 0, submittedCount_ = 0;
  cl_uint bounceCounts_[2] = {0, 0};
  FrameParams frame_{};
  std::uint64_t pixels_ = 0;
};

}  // namespace

std::unique_ptr<StageRunner> makeClStageRunner(const DeviceInfo& device, std::size_t workGroupSize,
                                               BvhLayout layout, bool profiling, unsigned lanes) {
  return std::make_unique<ClStageRunner>(device, workGroupSize, layout, profiling, lanes);
}

std::unique_ptr<StageRunner> makeStageRunner(const DeviceInfo& device, std::size_t workGroupSize,
                                             BvhLayout layout, bool profiling, unsigned lanes) {
  if (device.isHost) {
    resolveStageLayout(layout, device);  // the host backend's layout rule (Binary is bad input)
    resolveLanes(lanes, device);         // (the host backend runs the scalar bodies; W is checked)
    return makeHostStageRunner();
  }
  return makeClStageRunner(device, workGroupSize, layout, profiling, lanes);
}

}  // namespace montecl
