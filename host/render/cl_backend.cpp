// cl_backend.cpp: the OpenCL backend of the wave loop: one ClSession (context, in-order queue,
// cached kernel program), the per-render device buffers, and one kernel launch per stage. Queue
// counters are reset on the device; the host never reads a queue count back to size a launch
// (kernels return past the device-side count), only once per wave for the statistics.
#include <algorithm>

#include "cl/cl_session.h"
#include "render/bvh_buffer.h"
#include "render/stage_runner.h"
#include "util/errors.h"

namespace montecl {
namespace {

class ClStageRunner final : public StageRunner {
 public:
  ClStageRunner(const DeviceInfo& device, std::size_t workGroupSize, BvhLayout layout)
      : cl_(device, workGroupSize, /*profiling=*/false, layout), generate_(cl_.kernel("generate")), intersectCamera_(cl_.kernel("intersect")),
        intersectBounce_(cl_.kernel("intersect")), shadeAo_(cl_.kernel("shade_ao")),
        shadeDirect_(cl_.kernel("shade_direct")), shadeDirectHit_(cl_.kernel("shade_direct_hit")),
        intersectShadow_(cl_.kernel("intersect_shadow")), accumulate_(cl_.kernel("accumulate")),
        recordAov_(cl_.kernel("record_aov")), accumulateAov_(cl_.kernel("accumulate_aov")) {}

  std::uint64_t maxAllocBytes() const override { return cl_.device().maxAllocBytes; }
  BvhLayout bvhLayout() const override { return cl_.layout(); }
  bool programFromCache() const override { return cl_.build().fromCache; }
  double programBuildMs() const override { return cl_.build().buildMs; }

  void setup(const StageInputs& in) override {
    const std::uint64_t wave = in.wave, slots = in.frame.shadowSlots;
    pixels_ = std::uint64_t(in.frame.width) * in.frame.height;
    frameBuf_ = cl_.upload(std::vector<FrameParams>{in.frame});
    nodes_ = uploadBvhNodes(cl_, *in.bvh);
    tris_ = cl_.upload(in.bvh->triangles);
    materials_ = cl_.upload(in.materials);
    emitters_ = cl_.upload(in.emitters);
    rays_ = cl_.scratch<Ray>(wave);
    hits_ = cl_.scratch<Hit>(wave);
    bounce_ = cl_.scratch<Ray>(in.direct ? wave : 1);
    bounceHits_ = cl_.scratch<Hit>(in.direct ? wave : 1);
    radiance_ = cl_.scratch<cl_float4>(wave);
    shadowContrib_ = cl_.scratch<cl_float4>(wave * slots);
    shadowQueue_ = cl_.scratch<ShadowWork>(wave * slots);
    rayCount_ = cl_.buffer<cl_uint>(1);
    queueCount_ = cl_.buffer<cl_uint>(1);
    frame_ = in.frame;
    std::vector<cl_uint> all(pixels_);
    for (std::uint64_t p = 0; p < pixels_; ++p) all[p] = cl_uint(p);
    active_ = cl_.upload(all, CL_MEM_READ_WRITE);
    aovs_ = in.aovs;
    aov_ = cl_.scratch<cl_float4>(in.aovs ? 2 * wave : 1);
    aovSum_ = cl_.buffer<cl_float4>(in.aovs ? 2 * pixels_ : 1);
    sum_ = cl_.buffer<cl_float4>(pixels_);
    sumSq_ = cl_.buffer<cl_float4>(pixels_);
    // Cleared by writes, not clEnqueueFillBuffer: Oclgrind's uninitialised-memory check does not
    // count a fill as initialising memory, and a write costs the same here.
    const std::vector<cl_float4> zeros((aovs_ ? 2 : 1) * pixels_, cl_float4{{0.0f, 0.0f, 0.0f, 0.0f}});
    cl_.queue().enqueueWriteBuffer(sum_, CL_TRUE, 0, pixels_ * sizeof(cl_float4), zeros.data());
    cl_.queue().enqueueWriteBuffer(sumSq_, CL_TRUE, 0, pixels_ * sizeof(cl_float4), zeros.data());
    if (aovs_) cl_.queue().enqueueWriteBuffer(aovSum_, CL_TRUE, 0, 2 * pixels_ * sizeof(cl_float4), zeros.data());

    // Arguments that stay the same for every wave; waveStart and waveCount are set per wave.
    const cl_ulong noStart = 0;
    const cl_uint noCount = 0;
    setArgs(generate_, frameBuf_, noStart, noCount, rays_, active_);
    setArgs(intersectCamera_, nodes_, tris_, rays_, rayCount_, hits_);
    setArgs(intersectBounce_, nodes_, tris_, bounce_, rayCount_, bounceHits_);
    setArgs(shadeAo_, frameBuf_, noStart, noCount, tris_, rays_, hits_, radiance_, shadowContrib_, shadowQueue_,
            queueCount_, active_);
    setArgs(shadeDirect_, frameBuf_, noStart, noCount, tris_, materials_, emitters_, rays_, hits_, radiance_,
            shadowContrib_, shadowQueue_, queueCount_, bounce_, active_);
    setArgs(shadeDirectHit_, frameBuf_, noCount, tris_, materials_, rays_, hits_, bounce_, bounceHits_,
            shadowContrib_);
    setArgs(intersectShadow_, nodes_, tris_, shadowQueue_, queueCount_, shadowContrib_);
    setArgs(accumulate_, frameBuf_, noStart, noCount, radiance_, shadowContrib_, sum_, sumSq_, active_);
    setArgs(recordAov_, tris_, materials_, rays_, hits_, noCount, aov_);
    setArgs(accumulateAov_, frameBuf_, noStart, noCount, aov_, aovSum_, active_);
  }

  void setActivePixels(const std::vector<std::uint32_t>& pixels) override {
    frame_.activeCount = cl_uint(pixels.size());
    cl_.queue().enqueueWriteBuffer(frameBuf_, CL_TRUE, 0, sizeof(FrameParams), &frame_);
    if (!pixels.empty())
      cl_.queue().enqueueWriteBuffer(active_, CL_TRUE, 0, pixels.size() * sizeof(cl_uint), pixels.data());
  }

  void beginWave(std::uint64_t waveStart, std::uint32_t count) override {
    count_ = count;
    const cl_ulong start = waveStart;
    const cl_uint n = count;
    // Counters reset by (non-blocking) writes from members that outlive the wave (see setup).
    counters_[0] = n;
    counters_[1] = 0;
    cl_.queue().enqueueWriteBuffer(rayCount_, CL_FALSE, 0, sizeof(cl_uint), &counters_[0]);
    cl_.queue().enqueueWriteBuffer(queueCount_, CL_FALSE, 0, sizeof(cl_uint), &counters_[1]);
    for (cl::Kernel* k : {&generate_, &shadeAo_, &shadeDirect_, &accumulate_}) {
      k->setArg(1, start);
      k->setArg(2, n);
    }
    shadeDirectHit_.setArg(1, n);
    recordAov_.setArg(4, n);
    accumulateAov_.setArg(1, start);
    accumulateAov_.setArg(2, n);
  }

  void generate() override { cl_.launch(generate_, count_); }
  void intersectCamera() override { cl_.launch(intersectCamera_, count_); }
  void shadeAo() override { cl_.launch(shadeAo_, count_); }
  void shadeDirect() override { cl_.launch(shadeDirect_, count_); }
  void intersectBounce() override { cl_.launch(intersectBounce_, count_); }
  void shadeDirectHit() override { cl_.launch(shadeDirectHit_, count_); }
  void intersectShadow(std::uint64_t maxQueries) override { cl_.launch(intersectShadow_, maxQueries); }
  void accumulate(std::uint64_t pixelsTouched) override { cl_.launch(accumulate_, pixelsTouched); }
  void recordAov() override { cl_.launch(recordAov_, count_); }
  void accumulateAov(std::uint64_t pixelsTouched) override { cl_.launch(accumulateAov_, pixelsTouched); }

  std::uint32_t finishWave() override {
    cl_uint shadowCount = 0;
    cl_.queue().enqueueReadBuffer(queueCount_, CL_TRUE, 0, sizeof(cl_uint), &shadowCount);
    return shadowCount;
  }

  void readFilm(Film& film) override {
    film.mean.resize(pixels_);
    film.m2.resize(pixels_);
    cl_.queue().enqueueReadBuffer(sum_, CL_FALSE, 0, pixels_ * sizeof(cl_float4), film.mean.data());
    cl_.queue().enqueueReadBuffer(sumSq_, CL_TRUE, 0, pixels_ * sizeof(cl_float4), film.m2.data());
    if (aovs_) {
      film.aovSum.resize(2 * pixels_);
      cl_.queue().enqueueReadBuffer(aovSum_, CL_TRUE, 0, 2 * pixels_ * sizeof(cl_float4), film.aovSum.data());
    }
  }

 private:
  ClSession cl_;
  cl::Kernel generate_, intersectCamera_, intersectBounce_, shadeAo_, shadeDirect_, shadeDirectHit_,
      intersectShadow_, accumulate_, recordAov_, accumulateAov_;
  cl::Buffer frameBuf_, nodes_, tris_, materials_, emitters_, rays_, hits_, bounce_, bounceHits_, radiance_,
      shadowContrib_, shadowQueue_, rayCount_, queueCount_, sum_, sumSq_, active_, aov_, aovSum_;
  bool aovs_ = false;
  cl_uint counters_[2] = {0, 0};
  FrameParams frame_{};
  std::uint64_t pixels_ = 0;
  std::uint32_t count_ = 0;
};

}  // namespace

std::unique_ptr<StageRunner> makeClStageRunner(const DeviceInfo& device, std::size_t workGroupSize,
                                               BvhLayout layout) {
  return std::make_unique<ClStageRunner>(device, workGroupSize, layout);
}

std::unique_ptr<StageRunner> makeStageRunner(const DeviceInfo& device, std::size_t workGroupSize,
                                             BvhLayout layout) {
  if (device.isHost) {
    if (layout == BvhLayout::Binary)
      throw InputError("--bvh-layout binary: the host backend traverses the wide BVH only");
    return makeHostStageRunner();
  }
  return makeClStageRunner(device, workGroupSize, layout);
}

}  // namespace montecl
