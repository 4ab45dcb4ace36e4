// host_backend.cpp: the host backend (`--device host`): the same stage bodies the OpenCL kernels
// run (kernels/stages/*.h, compiled here as C++ through compat.h), as loops over a launch's items
// on the CPU, without any OpenCL driver; arguments come by name from HostBindings
// (render/stage_bindings.h). Items are split into contiguous chunks over a few std::threads; every
// item writes only its own outputs and every occlusion query its own slot, so the image does not
// depend on the thread count or on the shadow queue's order. Compiled with -ffp-contract=off
// (CMakeLists.txt), matching `#pragma OPENCL FP_CONTRACT OFF` in the kernels.
#include <algorithm>
#include <chrono>
#include <limits>
#include <thread>

#include "render/scene_tables.h"
#include "render/stage_runner.h"
#include "util/parallel_for.h"

namespace montecl {
namespace {

// Work below this many items runs on the calling thread (thread start-up costs more).
constexpr std::uint64_t kMinItemsPerThread = 2048;

class HostStageRunner final : public StageRunner {
 public:
  HostStageRunner() : threads_(std::max(1u, std::thread::hardware_concurrency())) {}

  std::uint64_t maxAllocBytes() const override { return std::numeric_limits<std::uint64_t>::max() / 4; }
  BvhLayout bvhLayout() const override { return BvhLayout::Wide; }

  void setup(const StageInputs& in) override {
    frame_ = in.frame;
    nodes_ = in.bvh->wideNodes();
    tables_.view(in);  // (not copied: the tables are read only, and texels can be large)
    const WaveShape shape = setupShape(in);
#define MCL_HOST_ALLOC(name, T, per, need) name##_.assign(bufferCount(Per::per, Need::need, shape), T{});
#define MCL_HOST_FILM_ALLOC(name, per, need) name##_.assign(bufferCount(Per::per, Need::need, shape), float4(0.0f));
    MCL_WAVE_BUFFERS(MCL_HOST_ALLOC)
    MCL_FILM_BUFFERS(MCL_HOST_FILM_ALLOC)
#undef MCL_HOST_ALLOC
#undef MCL_HOST_FILM_ALLOC
    const std::uint64_t pixels = shape.pixels;
    active_.resize(pixels);
    for (std::uint64_t p = 0; p < pixels; ++p) active_[p] = uint(p);
    aovs_ = shape.aovs;
    splits_ = shape.splits;
    if (const Film* f = in.initialFilm) {  // a resumed film: its words, count bits in the w lanes
      std::vector<glm::vec4> meanWords, meanLoWords;
      f->packCounts(meanWords, meanLoWords);
      const auto load = [&](std::vector<float4>& to, const std::vector<glm::vec4>& part) {
        const std::vector<glm::vec4>& from = &part == &f->mean ? meanWords : &part == &f->meanLo ? meanLoWords : part;
        for (std::size_t i = 0; i < to.size() && i < from.size(); ++i)
          to[i] = float4(from[i].x, from[i].y, from[i].z, from[i].w);
      };
#define MCL_HOST_FILM_LOAD(name, per, need) \
  if (needed(Need::need, shape)) load(name##_, f->name);
      MCL_FILM_BUFFERS(MCL_HOST_FILM_LOAD)
#undef MCL_HOST_FILM_LOAD
    }
    bind();
  }

  void setActivePixels(const std::vector<std::uint32_t>& pixels, unsigned blockShift) override {
    active_ = pixels;
    if (active_.empty()) active_.resize(1);
    frame_.activeCount = uint(pixels.size());
    frame_.sampleBlockShift = blockShift;
    bind();
  }

  void beginWave(std::uint64_t waveStart, std::uint32_t count) override {
    bindings_.waveStart = waveStart;
    bindings_.waveCount = count;
    *bindings_.rayCount = count;  // (the current ray count: path bounces swap it)
    queueCount_ = 0;
    nanRays_ = 0;
    packedLanes_ = aloneLanes_ = 0;
  }

  void launch(Stage s, std::uint64_t items, RayInput rays) override {
    const auto start = std::chrono::steady_clock::now();  // --profile: host timers
    withHostStageArgs(s, bindings_.forRays(rays), [&](const auto& args) {
      // The stage body for this args type, found by overload resolution (stage_<name>(&args, i)).
      parallelFor(items, threads_, kMinItemsPerThread, [&](std::size_t i) { runStage(&args, uint(i)); });
    });
    if (profile_)
      profile_->add(stageProfileName(s, rays),
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }

  void startBounce(std::uint32_t bounce) override {
    bindings_.pathBounce = bounce;
    queueCount_ = 0;
    *bindings_.nextCount = 0;
  }

  void endBounce() override {
    HostBindings& b = bindings_;
    std::swap(b.rays, b.nextRays);
    std::swap(b.pathIds, b.nextPathIds);
    std::swap(b.rayCount, b.nextCount);
  }

  BounceCounts readBounceCounts() override { return BounceCounts{*bindings_.rayCount, queueCount_}; }

  // (The stages ran in launch(): a wave's counts are final when it is submitted.)
  void submitWave() override {
    submitted_[(firstSubmitted_ + submittedCount_++) % 2] = {queueCount_, nanRays_};
    if (profile_) {
      profile_->packedLanes += packedLanes_;
      profile_->aloneLanes += aloneLanes_;
    }
  }
  WaveCounts waitWave() override {
    const WaveCounts c = submitted_[firstSubmitted_];
    firstSubmitted_ = (firstSubmitted_ + 1) % 2;
    --submittedCount_;
    return c;
  }

  void readFilm(Film& film) override {
    film.mean = mean_;
    film.meanLo = meanLo_;
    film.m2 = m2_;
    film.m2Lo = m2Lo_;
    film.unpackCounts();
    if (aovs_) film.aovSum.assign(aovSum_.begin(), aovSum_.end());
    if (splits_) film.split.assign(split_.begin(), split_.end());
  }

  // The film's vectors move out (no copy); every other buffer is freed.
  void finish(Film& film) override {
    film.mean = std::move(mean_);
    film.meanLo = std::move(meanLo_);
    film.m2 = std::move(m2_);
    film.m2Lo = std::move(m2Lo_);
    film.unpackCounts();
    if (aovs_) film.aovSum = std::move(aovSum_);
    if (splits_) film.split = std::move(split_);
#define MCL_HOST_RELEASE(name, ...) name##_ = {};
    MCL_WAVE_BUFFERS(MCL_HOST_RELEASE)
    MCL_FILM_BUFFERS(MCL_HOST_RELEASE)
#undef MCL_HOST_RELEASE
    active_ = {}, nodes_ = {};
    tables_.release();
    bind();
  }

 private:
#define MCL_HOST_RUN_STAGE(stage) \
  static void runStage(const stage##_args* a, uint i) { stage_##stage(a, i); }
  MCL_STAGES(MCL_HOST_RUN_STAGE)
#undef MCL_HOST_RUN_STAGE

  // Points the bindings at the vectors (after any of them may have moved).
  void bind() {
    HostBindings& b = bindings_;
    b.frame = &frame_;
    b.nodes = nodes_.data();
#define MCL_HOST_BIND_TABLE(name, T, dummy) b.name = tables_.name ? tables_.name->data() : nullptr;
    MCL_SCENE_TABLES(MCL_HOST_BIND_TABLE)
#undef MCL_HOST_BIND_TABLE
    b.active = active_.data();
#define MCL_HOST_BIND(name, ...) b.name = name##_.data();
#define MCL_HOST_BIND_COUNTER(name) b.name = &name##_;
    MCL_WAVE_BUFFERS(MCL_HOST_BIND)
    MCL_FILM_BUFFERS(MCL_HOST_BIND)
    MCL_WAVE_COUNTERS(MCL_HOST_BIND_COUNTER)
#undef MCL_HOST_BIND
#undef MCL_HOST_BIND_COUNTER
  }

  unsigned threads_;
  HostBindings bindings_;
  FrameParams frame_{};
  bool aovs_ = false;
  std::uint64_t splits_ = 0;  // sobol sub-sequences with film accumulators (Film::split)
  std::vector<uint> active_;
  std::vector<WideNode> nodes_;
  SceneTables tables_;  // the read-only scene tables, viewed in the caller's StageInputs
  // The wave buffers, counters and film (render/wave_buffers.h); queueCount_ and nanRays_ are
  // incremented atomically by the stages.
#define MCL_HOST_VECTOR(name, T, per, need) std::vector<T> name##_;
#define MCL_HOST_FILM_VECTOR(name, per, need) std::vector<float4> name##_;
#define MCL_HOST_COUNTER(name) uint name##_ = 0;
  MCL_WAVE_BUFFERS(MCL_HOST_VECTOR)
  MCL_FILM_BUFFERS(MCL_HOST_FILM_VECTOR)
  MCL_WAVE_COUNTERS(MCL_HOST_COUNTER)
#undef MCL_HOST_VECTOR
#undef MCL_HOST_FILM_VECTOR
#undef MCL_HOST_COUNTER
  WaveCounts submitted_[2];  // counts of the waves submitted and not yet waited for, oldest first
  unsigned firstSubmitted_ = 0, submittedCount_ = 0;
};

}  // namespace

std::unique_ptr<StageRunner> makeHostStageRunner() { return std::make_unique<HostStageRunner>(); }

}  // namespace montecl
