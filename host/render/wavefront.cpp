// wavefront.cpp: the render loop. Per wave: reset the queue counters on the device, then
// generate -> intersect -> shade_ao -> intersect_shadow -> accumulate; the host never reads a
// queue count back to size a launch (kernels return past the device-side count).
#include "render/wavefront.h"

#include <algorithm>
#include <chrono>
#include <iostream>

#include "cl/cl_errors.h"
#include "cl/kernel_source.h"
#include "cl/program_cache.h"
#include "render/frame_params.h"
#include "util/errors.h"

namespace montecl {
namespace {

constexpr const char* kBuildOptions = "-cl-std=CL1.2";

// Bytes of per-wave buffers for one pixel sample with `slots` occlusion queries.
std::uint64_t bytesPerItem(std::uint32_t slots) {
  return sizeof(Ray) + sizeof(Hit) + sizeof(cl_float4) + slots * (sizeof(cl_float4) + sizeof(ShadowWork));
}

template <typename T>
cl::Buffer deviceBuffer(const cl::Context& ctx, cl_mem_flags flags, std::size_t count) {
  return cl::Buffer(ctx, flags, std::max<std::size_t>(count, 1) * sizeof(T));
}

template <typename T>
cl::Buffer uploadBuffer(const cl::Context& ctx, const std::vector<T>& data) {
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, data.size() * sizeof(T),
                    const_cast<T*>(data.data()));
}

}  // namespace

struct WavefrontRenderer::Impl {
  DeviceInfo device;
  RenderOptions options;
  cl::Context context;
  cl::CommandQueue queue;
  ProgramBuild build;
  cl::Kernel generate, intersect, shadeAo, intersectShadow, accumulate;

  std::size_t localSize(const cl::Kernel& k) const {
    std::size_t maxSize = k.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device.device);
    std::size_t want = options.workGroupSize ? options.workGroupSize : 64;
    return std::max<std::size_t>(1, std::min(want, maxSize));
  }

  // Launches k over n work items (rounded up to whole work-groups); names the kernel on failure.
  void launch(cl::Kernel& k, const char* name, std::uint64_t n) {
    if (n == 0) return;
    std::size_t local = localSize(k);
    std::size_t global = ((n + local - 1) / local) * local;
    try {
      queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NDRange(local));
    } catch (const cl::Error& e) {
      throw RuntimeError(std::string("kernel ") + name + ": " + describeClError(e));
    }
  }
};

WavefrontRenderer::WavefrontRenderer(const DeviceInfo& device, const RenderOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = device;
  m.options = options;
  m.context = cl::Context(device.device);
  m.queue = cl::CommandQueue(m.context, device.device);
  m.build = buildProgramCached(m.context, device, expandedKernelSource("montecl.cl"), kBuildOptions);
  m.generate = cl::Kernel(m.build.program, "generate");
  m.intersect = cl::Kernel(m.build.program, "intersect");
  m.shadeAo = cl::Kernel(m.build.program, "shade_ao");
  m.intersectShadow = cl::Kernel(m.build.program, "intersect_shadow");
  m.accumulate = cl::Kernel(m.build.program, "accumulate");
}

WavefrontRenderer::~WavefrontRenderer() = default;

bool WavefrontRenderer::programFromCache() const { return impl_->build.fromCache; }
double WavefrontRenderer::programBuildMs() const { return impl_->build.buildMs; }

Film WavefrontRenderer::render(const Scene& scene, const Bvh& bvh, RenderStats& stats,
                               const ProgressFn& progress) {
  Impl& m = *impl_;
  const std::uint32_t slots = 1;
  const FrameParams frame = makeFrameParams(scene.camera, scene.render, slots);
  const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
  const std::uint64_t total = pixels * std::uint64_t(scene.render.spp);

  // Wave size: the memory budget, the device's largest allocation, and 32-bit item indices.
  std::uint64_t wave = m.options.waveSize;
  if (wave == 0) wave = std::max<std::uint64_t>(1, m.options.memoryBudget / bytesPerItem(slots));
  wave = std::min<std::uint64_t>(wave, m.device.maxAllocBytes / (slots * sizeof(ShadowWork)));
  wave = std::min<std::uint64_t>(wave, 0xffffffffull / slots);
  wave = std::max<std::uint64_t>(1, std::min(wave, total));
  if (pixels * sizeof(cl_float4) > m.device.maxAllocBytes)
    throw RuntimeError("image of " + std::to_string(pixels) + " pixels needs a buffer larger than the device's "
                       "maximum allocation (" + std::to_string(m.device.maxAllocBytes) + " bytes)");
  stats = RenderStats{};
  stats.waveSize = wave;

  const cl::Context& ctx = m.context;
  cl::Buffer frameBuf(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(frame), const_cast<FrameParams*>(&frame));
  cl::Buffer nodes = uploadBuffer(ctx, bvh.nodes);
  cl::Buffer tris = uploadBuffer(ctx, bvh.triangles);
  cl::Buffer rays = deviceBuffer<Ray>(ctx, CL_MEM_READ_WRITE, wave);
  cl::Buffer hits = deviceBuffer<Hit>(ctx, CL_MEM_READ_WRITE, wave);
  cl::Buffer radiance = deviceBuffer<cl_float4>(ctx, CL_MEM_READ_WRITE, wave);
  cl::Buffer shadowContrib = deviceBuffer<cl_float4>(ctx, CL_MEM_READ_WRITE, wave * slots);
  cl::Buffer shadowQueue = deviceBuffer<ShadowWork>(ctx, CL_MEM_READ_WRITE, wave * slots);
  cl::Buffer rayCount = deviceBuffer<cl_uint>(ctx, CL_MEM_READ_WRITE, 1);
  cl::Buffer queueCount = deviceBuffer<cl_uint>(ctx, CL_MEM_READ_WRITE, 1);
  cl::Buffer sum = deviceBuffer<cl_float4>(ctx, CL_MEM_READ_WRITE, pixels);
  cl::Buffer sumSq = deviceBuffer<cl_float4>(ctx, CL_MEM_READ_WRITE, pixels);
  const cl_float4 zero4 = {{0.0f, 0.0f, 0.0f, 0.0f}};
  m.queue.enqueueFillBuffer(sum, zero4, 0, pixels * sizeof(cl_float4));
  m.queue.enqueueFillBuffer(sumSq, zero4, 0, pixels * sizeof(cl_float4));

  m.generate.setArg(0, frameBuf);
  m.generate.setArg(3, rays);
  m.intersect.setArg(0, nodes);
  m.intersect.setArg(1, tris);
  m.intersect.setArg(2, rays);
  m.intersect.setArg(3, rayCount);
  m.intersect.setArg(4, hits);
  m.shadeAo.setArg(0, frameBuf);
  m.shadeAo.setArg(3, tris);
  m.shadeAo.setArg(4, rays);
  m.shadeAo.setArg(5, hits);
  m.shadeAo.setArg(6, radiance);
  m.shadeAo.setArg(7, shadowContrib);
  m.shadeAo.setArg(8, shadowQueue);
  m.shadeAo.setArg(9, queueCount);
  m.intersectShadow.setArg(0, nodes);
  m.intersectShadow.setArg(1, tris);
  m.intersectShadow.setArg(2, shadowQueue);
  m.intersectShadow.setArg(3, queueCount);
  m.intersectShadow.setArg(4, shadowContrib);
  m.accumulate.setArg(0, frameBuf);
  m.accumulate.setArg(3, radiance);
  m.accumulate.setArg(4, shadowContrib);
  m.accumulate.setArg(5, sum);
  m.accumulate.setArg(6, sumSq);

  if (m.options.verbose)
    std::cerr << "montecl: wave of " << wave << " pixel samples (" << (wave * bytesPerItem(slots) >> 20)
              << " MiB), " << (total + wave - 1) / wave << " waves\n";

  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t first = std::uint64_t(m.options.firstSample) * pixels;
  std::vector<cl_uint> shadowCounts;
  for (std::uint64_t done = 0; done < total;) {
    const cl_ulong waveStart = first + done;
    const cl_uint count = cl_uint(std::min(wave, total - done));
    const cl_uint zero = 0;
    m.queue.enqueueFillBuffer(rayCount, count, 0, sizeof(cl_uint));
    m.queue.enqueueFillBuffer(queueCount, zero, 0, sizeof(cl_uint));
    for (cl::Kernel* k : {&m.generate, &m.shadeAo, &m.accumulate}) {
      k->setArg(1, waveStart);
      k->setArg(2, count);
    }
    m.launch(m.generate, "generate", count);
    m.launch(m.intersect, "intersect", count);
    m.launch(m.shadeAo, "shade_ao", count);
    m.launch(m.intersectShadow, "intersect_shadow", std::uint64_t(count) * slots);
    m.launch(m.accumulate, "accumulate", std::min<std::uint64_t>(count, pixels));
    cl_uint shadowCount = 0;
    m.queue.enqueueReadBuffer(queueCount, CL_TRUE, 0, sizeof(cl_uint), &shadowCount);
    done += count;
    stats.waves++;
    stats.cameraRays += count;
    stats.shadowRays += shadowCount;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(done, total, stats);
  }

  Film film;
  film.width = int(frame.width);
  film.height = int(frame.height);
  film.sum.resize(pixels);
  film.sumSq.resize(pixels);
  m.queue.enqueueReadBuffer(sum, CL_FALSE, 0, pixels * sizeof(cl_float4), film.sum.data());
  m.queue.enqueueReadBuffer(sumSq, CL_TRUE, 0, pixels * sizeof(cl_float4), film.sumSq.data());
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return film;
}

}  // namespace montecl
