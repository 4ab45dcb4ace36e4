// host_backend.cpp: the host backend (`--device host`): the same stage_* functions the OpenCL
// kernels wrap (kernels/shared/stages*.h, compiled here as C++ through compat.h) run as loops over
// the wave's items on the CPU, without any OpenCL driver. Items are split into contiguous chunks
// over a few std::threads; every item writes only its own outputs and every occlusion query its
// own slot, so the image does not depend on the thread count or on the shadow queue's order.
// Compiled with -ffp-contract=off (CMakeLists.txt), matching `#pragma OPENCL FP_CONTRACT OFF` in
// the kernels.
#include <algorithm>
#include <limits>
#include <thread>

#include "kernels/shared/stages_aov.h"
#include "kernels/shared/stages_direct.h"
#include "render/stage_runner.h"

namespace montecl {
namespace {

// Work below this many items runs on the calling thread (thread start-up costs more).
constexpr std::uint64_t kMinItemsPerThread = 2048;

class HostStageRunner final : public StageRunner {
 public:
  explicit HostStageRunner(unsigned threads)
      : threads_(threads ? threads : std::max(1u, std::thread::hardware_concurrency())) {}

  std::uint64_t maxAllocBytes() const override { return std::numeric_limits<std::uint64_t>::max() / 4; }
  BvhLayout bvhLayout() const override { return BvhLayout::Wide; }

  void setup(const StageInputs& in) override {
    frame_ = in.frame;
    nodes_ = in.bvh->wideNodes();
    tris_ = in.bvh->triangles;
    materials_ = in.materials;
    emitters_ = in.emitters;
    if (materials_.empty()) materials_.resize(1);
    if (emitters_.empty()) emitters_.resize(1);
    if (nodes_.empty()) nodes_.push_back(emptyWideNode());  // an empty BVH: one node of empty slots, as on the device
    const std::uint64_t wave = std::max<std::uint64_t>(1, in.wave), slots = frame_.shadowSlots;
    rays_.assign(wave, Ray{});
    hits_.assign(wave, Hit{});
    bounce_.assign(in.direct ? wave : 1, Ray{});
    bounceHits_.assign(in.direct ? wave : 1, Hit{});
    radiance_.assign(wave, float4(0.0f));
    shadowContrib_.assign(wave * slots, float4(0.0f));
    queue_.assign(wave * slots, ShadowWork{});
    const std::uint64_t pixels = std::uint64_t(frame_.width) * frame_.height;
    active_.resize(pixels);
    for (std::uint64_t p = 0; p < pixels; ++p) active_[p] = uint(p);
    aovs_ = in.aovs;
    aov_.assign(in.aovs ? 2 * wave : 1, float4(0.0f));
    aovSum_.assign(in.aovs ? 2 * pixels : 1, float4(0.0f));
    sum_.assign(pixels, float4(0.0f));
    sumSq_.assign(pixels, float4(0.0f));
  }

  void setActivePixels(const std::vector<std::uint32_t>& pixels) override {
    active_ = pixels;
    if (active_.empty()) active_.resize(1);
    frame_.activeCount = uint(pixels.size());
  }

  void beginWave(std::uint64_t waveStart, std::uint32_t count) override {
    waveStart_ = waveStart;
    count_ = count;
    queueCount_ = 0;
  }

  void generate() override {
    parallelFor(count_, [&](uint i) { stage_generate(&frame_, active_.data(), waveStart_, i, rays_.data()); });
  }
  void intersectCamera() override {
    parallelFor(count_, [&](uint i) { stage_intersect(nodes_.data(), tris_.data(), rays_.data(), i, hits_.data()); });
  }
  void intersectBounce() override {
    parallelFor(count_, [&](uint i) {
      stage_intersect(nodes_.data(), tris_.data(), bounce_.data(), i, bounceHits_.data());
    });
  }
  void shadeAo() override {
    parallelFor(count_, [&](uint i) {
      stage_shade_ao(&frame_, active_.data(), waveStart_, tris_.data(), rays_.data(), hits_.data(), i, radiance_.data(),
                     shadowContrib_.data(), queue_.data(), &queueCount_);
    });
  }
  void shadeDirect() override {
    parallelFor(count_, [&](uint i) {
      stage_shade_direct(&frame_, active_.data(), waveStart_, tris_.data(), materials_.data(), emitters_.data(), rays_.data(),
                         hits_.data(), i, radiance_.data(), shadowContrib_.data(), queue_.data(), &queueCount_,
                         bounce_.data());
    });
  }
  void shadeDirectHit() override {
    parallelFor(count_, [&](uint i) {
      stage_shade_direct_hit(&frame_, tris_.data(), materials_.data(), rays_.data(), hits_.data(), bounce_.data(),
                             bounceHits_.data(), i, shadowContrib_.data());
    });
  }
  void intersectShadow(std::uint64_t maxQueries) override {
    const std::uint64_t n = std::min<std::uint64_t>(maxQueries, queueCount_);
    parallelFor(n, [&](uint k) {
      stage_intersect_shadow(nodes_.data(), tris_.data(), queue_.data(), k, shadowContrib_.data());
    });
  }
  void accumulate(std::uint64_t pixelsTouched) override {
    parallelFor(pixelsTouched, [&](uint j) {
      stage_accumulate(&frame_, active_.data(), waveStart_, count_, j, radiance_.data(), shadowContrib_.data(), sum_.data(),
                       sumSq_.data());
    });
  }
  void recordAov() override {
    parallelFor(count_, [&](uint i) {
      stage_record_aov(tris_.data(), materials_.data(), rays_.data(), hits_.data(), i, aov_.data());
    });
  }
  void accumulateAov(std::uint64_t pixelsTouched) override {
    parallelFor(pixelsTouched, [&](uint j) {
      stage_accumulate_aov(&frame_, active_.data(), waveStart_, count_, j, aov_.data(), aovSum_.data());
    });
  }
  std::uint32_t finishWave() override { return queueCount_; }

  void readFilm(Film& film) override {
    film.mean.assign(sum_.begin(), sum_.end());
    film.m2.assign(sumSq_.begin(), sumSq_.end());
    if (aovs_) film.aovSum.assign(aovSum_.begin(), aovSum_.end());
  }

 private:
  // Runs body(i) for i in [0, n): contiguous chunks on up to threads_ threads.
  template <typename Body>
  void parallelFor(std::uint64_t n, const Body& body) {
    const std::uint64_t threads = std::min<std::uint64_t>(threads_, n / kMinItemsPerThread);
    if (threads <= 1) {
      for (std::uint64_t i = 0; i < n; ++i) body(uint(i));
      return;
    }
    std::vector<std::thread> pool;
    const std::uint64_t chunk = (n + threads - 1) / threads;
    for (std::uint64_t t = 1; t < threads; ++t)
      pool.emplace_back([&, t] {
        for (std::uint64_t i = t * chunk; i < std::min(n, (t + 1) * chunk); ++i) body(uint(i));
      });
    for (std::uint64_t i = 0; i < std::min(n, chunk); ++i) body(uint(i));
    for (std::thread& th : pool) th.join();
  }

  unsigned threads_;
  FrameParams frame_{};
  bool aovs_ = false;
  std::vector<float4> aov_, aovSum_;
  std::vector<uint> active_;
  std::vector<WideNode> nodes_;
  std::vector<Triangle> tris_;
  std::vector<Material> materials_;
  std::vector<Emitter> emitters_;
  std::vector<Ray> rays_, bounce_;
  std::vector<Hit> hits_, bounceHits_;
  std::vector<float4> radiance_, shadowContrib_, sum_, sumSq_;
  std::vector<ShadowWork> queue_;
  std::uint64_t waveStart_ = 0;
  std::uint32_t count_ = 0;
  volatile uint queueCount_ = 0;
};

}  // namespace

std::unique_ptr<StageRunner> makeHostStageRunner(unsigned threads) {
  return std::make_unique<HostStageRunner>(threads);
}

}  // namespace montecl
