// wavefront.cpp: the render loop. Per wave: reset the queue counters on the device, then
// generate -> intersect -> shade_ao -> intersect_shadow -> accumulate; the host never reads a
// queue count back to size a launch (kernels return past the device-side count).
#include "render/wavefront.h"

#include <algorithm>
#include <chrono>
#include <iostream>

#include "cl/cl_session.h"
#include "render/emitters.h"
#include "render/frame_params.h"
#include "util/errors.h"

namespace montecl {
namespace {

// Bytes of per-wave buffers for one pixel sample with `slots` occlusion queries.
std::uint64_t bytesPerItem(std::uint32_t slots, bool bounce) {
  return sizeof(Ray) + sizeof(Hit) + sizeof(cl_float4) + slots * (sizeof(cl_float4) + sizeof(ShadowWork)) +
         (bounce ? sizeof(Ray) + sizeof(Hit) : 0);
}

}  // namespace

struct WavefrontRenderer::Impl {
  Impl(const DeviceInfo& device, const RenderOptions& opts)
      : options(opts), cl(device, opts.workGroupSize), generate(cl.kernel("generate")),
        intersectCamera(cl.kernel("intersect")), intersectBounce(cl.kernel("intersect")),
        shadeAo(cl.kernel("shade_ao")), shadeDirect(cl.kernel("shade_direct")),
        shadeDirectHit(cl.kernel("shade_direct_hit")), intersectShadow(cl.kernel("intersect_shadow")),
        accumulate(cl.kernel("accumulate")) {}
  RenderOptions options;
  ClSession cl;
  cl::Kernel generate, intersectCamera, intersectBounce, shadeAo, shadeDirect, shadeDirectHit,
      intersectShadow, accumulate;
};

WavefrontRenderer::WavefrontRenderer(const DeviceInfo& device, const RenderOptions& options)
    : impl_(std::make_unique<Impl>(device, options)) {}

WavefrontRenderer::~WavefrontRenderer() = default;

bool WavefrontRenderer::programFromCache() const { return impl_->cl.build().fromCache; }
double WavefrontRenderer::programBuildMs() const { return impl_->cl.build().buildMs; }

namespace {

// Sets consecutive kernel arguments starting at index 0.
template <typename... Args>
void setArgs(cl::Kernel& k, const Args&... args) {
  cl_uint index = 0;
  (k.setArg(index++, args), ...);
}

std::vector<Material> deviceMaterials(const std::vector<MaterialDesc>& materials) {
  std::vector<Material> out;
  for (const MaterialDesc& m : materials) out.push_back({glm::vec4(m.albedo, 0.0f), glm::vec4(m.emission, 0.0f)});
  return out;
}

}  // namespace

Film WavefrontRenderer::render(const Scene& scene, const Bvh& bvh, RenderStats& stats,
                               const ProgressFn& progress) {
  Impl& m = *impl_;
  ClSession& cl = m.cl;
  const bool direct = scene.render.integrator == "direct";
  const std::uint32_t slots = direct ? std::uint32_t(scene.render.lightSamples) + 1 : 1;
  FrameParams frame = makeFrameParams(scene.camera, scene.render, slots);
  const EmitterTable emitters = direct ? buildEmitterTable(bvh, scene.materials) : EmitterTable{};
  frame.emitterCount = cl_uint(emitters.emitters.size());
  frame.emitterPower = emitters.totalPower;
  const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
  const std::uint64_t total = pixels * std::uint64_t(scene.render.spp);

  // Wave size: the memory budget, the device's largest allocation, and 32-bit item indices.
  const std::uint64_t maxAlloc = cl.device().maxAllocBytes;
  std::uint64_t wave = m.options.waveSize;
  if (wave == 0) wave = std::max<std::uint64_t>(1, m.options.memoryBudget / bytesPerItem(slots, direct));
  wave = std::min<std::uint64_t>(wave, maxAlloc / (slots * sizeof(ShadowWork)));
  wave = std::min<std::uint64_t>(wave, 0xffffffffull / slots);
  wave = std::max<std::uint64_t>(1, std::min(wave, total));
  for (std::uint64_t bytes : {pixels * sizeof(cl_float4), bvh.nodes.size() * sizeof(BvhNode),
                              bvh.triangles.size() * sizeof(Triangle)})
    if (bytes > maxAlloc)
      throw RuntimeError("a buffer of " + std::to_string(bytes) + " bytes does not fit the device's maximum "
                         "allocation of " + std::to_string(maxAlloc) + " bytes; use a smaller image or scene");
  stats = RenderStats{};
  stats.waveSize = wave;

  cl::Buffer frameBuf = cl.upload(std::vector<FrameParams>{frame});
  cl::Buffer nodes = cl.upload(bvh.nodes);
  cl::Buffer tris = cl.upload(bvh.triangles);
  cl::Buffer materials = cl.upload(deviceMaterials(scene.materials));
  cl::Buffer emitterBuf = cl.upload(emitters.emitters);
  cl::Buffer rays = cl.buffer<Ray>(wave);
  cl::Buffer hits = cl.buffer<Hit>(wave);
  cl::Buffer bounce = cl.buffer<Ray>(direct ? wave : 1);
  cl::Buffer bounceHits = cl.buffer<Hit>(direct ? wave : 1);
  cl::Buffer radiance = cl.buffer<cl_float4>(wave);
  cl::Buffer shadowContrib = cl.buffer<cl_float4>(wave * slots);
  cl::Buffer shadowQueue = cl.buffer<ShadowWork>(wave * slots);
  cl::Buffer rayCount = cl.buffer<cl_uint>(1);
  cl::Buffer queueCount = cl.buffer<cl_uint>(1);
  cl::Buffer sum = cl.buffer<cl_float4>(pixels);
  cl::Buffer sumSq = cl.buffer<cl_float4>(pixels);
  const cl_float4 zero4 = {{0.0f, 0.0f, 0.0f, 0.0f}};
  cl.queue().enqueueFillBuffer(sum, zero4, 0, pixels * sizeof(cl_float4));
  cl.queue().enqueueFillBuffer(sumSq, zero4, 0, pixels * sizeof(cl_float4));

  // Arguments that stay the same for every wave; waveStart and waveCount are set per wave.
  const cl_ulong noStart = 0;
  const cl_uint noCount = 0;
  setArgs(m.generate, frameBuf, noStart, noCount, rays);
  setArgs(m.intersectCamera, nodes, tris, rays, rayCount, hits);
  setArgs(m.intersectBounce, nodes, tris, bounce, rayCount, bounceHits);
  setArgs(m.shadeAo, frameBuf, noStart, noCount, tris, rays, hits, radiance, shadowContrib, shadowQueue, queueCount);
  setArgs(m.shadeDirect, frameBuf, noStart, noCount, tris, materials, emitterBuf, rays, hits, radiance, shadowContrib,
          shadowQueue, queueCount, bounce);
  setArgs(m.shadeDirectHit, frameBuf, noCount, tris, materials, rays, hits, bounce, bounceHits, shadowContrib);
  setArgs(m.intersectShadow, nodes, tris, shadowQueue, queueCount, shadowContrib);
  setArgs(m.accumulate, frameBuf, noStart, noCount, radiance, shadowContrib, sum, sumSq);

  if (m.options.verbose)
    std::cerr << "montecl: wave of " << wave << " pixel samples (" << (wave * bytesPerItem(slots, direct) >> 20)
              << " MiB), " << (total + wave - 1) / wave << " waves"
              << (direct ? ", " + std::to_string(emitters.emitters.size()) + " emitter triangles" : std::string())
              << "\n";

  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t first = std::uint64_t(m.options.firstSample) * pixels;
  for (std::uint64_t done = 0; done < total;) {
    const cl_ulong waveStart = first + done;
    const cl_uint count = cl_uint(std::min(wave, total - done));
    const cl_uint zero = 0;
    cl.queue().enqueueFillBuffer(rayCount, count, 0, sizeof(cl_uint));
    cl.queue().enqueueFillBuffer(queueCount, zero, 0, sizeof(cl_uint));
    for (cl::Kernel* k : {&m.generate, &m.shadeAo, &m.shadeDirect, &m.accumulate}) {
      k->setArg(1, waveStart);
      k->setArg(2, count);
    }
    m.shadeDirectHit.setArg(1, count);

    cl.launch(m.generate, count);
    cl.launch(m.intersectCamera, count);
    if (direct) {
      cl.launch(m.shadeDirect, count);
      cl.launch(m.intersectBounce, count);
      cl.launch(m.shadeDirectHit, count);
    } else {
      cl.launch(m.shadeAo, count);
    }
    cl.launch(m.intersectShadow, std::uint64_t(count) * slots);
    cl.launch(m.accumulate, std::min<std::uint64_t>(count, pixels));
    cl_uint shadowCount = 0;
    cl.queue().enqueueReadBuffer(queueCount, CL_TRUE, 0, sizeof(cl_uint), &shadowCount);

    done += count;
    stats.waves++;
    stats.cameraRays += count;
    stats.shadowRays += shadowCount;
    if (direct && scene.render.directSampling != "light") stats.cameraRays += count;  // BRDF rays
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(done, total, stats);
  }

  Film film;
  film.width = int(frame.width);
  film.height = int(frame.height);
  film.sum.resize(pixels);
  film.sumSq.resize(pixels);
  cl.queue().enqueueReadBuffer(sum, CL_FALSE, 0, pixels * sizeof(cl_float4), film.sum.data());
  cl.queue().enqueueReadBuffer(sumSq, CL_TRUE, 0, pixels * sizeof(cl_float4), film.sumSq.data());
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return film;
}

}  // namespace montecl
