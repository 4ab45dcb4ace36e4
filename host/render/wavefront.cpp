// wavefront.cpp: the render loop. Per wave: reset the queue counters on the device, then
// generate -> intersect -> shade_ao -> intersect_shadow -> accumulate; the host never reads a
// queue count back to size a launch (kernels return past the device-side count).
#include "render/wavefront.h"

#include <algorithm>
#include <chrono>
#include <iostream>

#include "cl/cl_session.h"
#include "render/frame_params.h"
#include "util/errors.h"

namespace montecl {
namespace {

// Bytes of per-wave buffers for one pixel sample with `slots` occlusion queries.
std::uint64_t bytesPerItem(std::uint32_t slots) {
  return sizeof(Ray) + sizeof(Hit) + sizeof(cl_float4) + slots * (sizeof(cl_float4) + sizeof(ShadowWork));
}

}  // namespace

struct WavefrontRenderer::Impl {
  Impl(const DeviceInfo& device, const RenderOptions& opts)
      : options(opts), cl(device, opts.workGroupSize), generate(cl.kernel("generate")),
        intersect(cl.kernel("intersect")), shadeAo(cl.kernel("shade_ao")),
        intersectShadow(cl.kernel("intersect_shadow")), accumulate(cl.kernel("accumulate")) {}
  RenderOptions options;
  ClSession cl;
  cl::Kernel generate, intersect, shadeAo, intersectShadow, accumulate;
};

WavefrontRenderer::WavefrontRenderer(const DeviceInfo& device, const RenderOptions& options)
    : impl_(std::make_unique<Impl>(device, options)) {}

WavefrontRenderer::~WavefrontRenderer() = default;

bool WavefrontRenderer::programFromCache() const { return impl_->cl.build().fromCache; }
double WavefrontRenderer::programBuildMs() const { return impl_->cl.build().buildMs; }

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
  wave = std::min<std::uint64_t>(wave, m.cl.device().maxAllocBytes / (slots * sizeof(ShadowWork)));
  wave = std::min<std::uint64_t>(wave, 0xffffffffull / slots);
  wave = std::max<std::uint64_t>(1, std::min(wave, total));
  if (pixels * sizeof(cl_float4) > m.cl.device().maxAllocBytes)
    throw RuntimeError("image of " + std::to_string(pixels) + " pixels needs a buffer larger than the device's "
                       "maximum allocation (" + std::to_string(m.cl.device().maxAllocBytes) + " bytes)");
  stats = RenderStats{};
  stats.waveSize = wave;

    cl::Buffer frameBuf = m.cl.upload(std::vector<FrameParams>{frame});
  cl::Buffer nodes = m.cl.upload(bvh.nodes);
  cl::Buffer tris = m.cl.upload(bvh.triangles);
  cl::Buffer rays = m.cl.buffer<Ray>(wave);
  cl::Buffer hits = m.cl.buffer<Hit>(wave);
  cl::Buffer radiance = m.cl.buffer<cl_float4>(wave);
  cl::Buffer shadowContrib = m.cl.buffer<cl_float4>(wave * slots);
  cl::Buffer shadowQueue = m.cl.buffer<ShadowWork>(wave * slots);
  cl::Buffer rayCount = m.cl.buffer<cl_uint>(1);
  cl::Buffer queueCount = m.cl.buffer<cl_uint>(1);
  cl::Buffer sum = m.cl.buffer<cl_float4>(pixels);
  cl::Buffer sumSq = m.cl.buffer<cl_float4>(pixels);
  const cl_float4 zero4 = {{0.0f, 0.0f, 0.0f, 0.0f}};
  m.cl.queue().enqueueFillBuffer(sum, zero4, 0, pixels * sizeof(cl_float4));
  m.cl.queue().enqueueFillBuffer(sumSq, zero4, 0, pixels * sizeof(cl_float4));

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
    m.cl.queue().enqueueFillBuffer(rayCount, count, 0, sizeof(cl_uint));
    m.cl.queue().enqueueFillBuffer(queueCount, zero, 0, sizeof(cl_uint));
    for (cl::Kernel* k : {&m.generate, &m.shadeAo, &m.accumulate}) {
      k->setArg(1, waveStart);
      k->setArg(2, count);
    }
    m.cl.launch(m.generate, count);
    m.cl.launch(m.intersect, count);
    m.cl.launch(m.shadeAo, count);
    m.cl.launch(m.intersectShadow, std::uint64_t(count) * slots);
    m.cl.launch(m.accumulate, std::min<std::uint64_t>(count, pixels));
    cl_uint shadowCount = 0;
    m.cl.queue().enqueueReadBuffer(queueCount, CL_TRUE, 0, sizeof(cl_uint), &shadowCount);
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
  m.cl.queue().enqueueReadBuffer(sum, CL_FALSE, 0, pixels * sizeof(cl_float4), film.sum.data());
  m.cl.queue().enqueueReadBuffer(sumSq, CL_TRUE, 0, pixels * sizeof(cl_float4), film.sumSq.data());
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return film;
}

}  // namespace montecl
