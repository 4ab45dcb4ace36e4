// ray_tracer.cpp: one-shot launches of the intersect and intersect_shadow stage kernels, their
// arguments bound by name (render/stage_bindings.h).
#include "render/ray_tracer.h"

#include <algorithm>

#include "render/device_materials.h"
#include "render/triangle_shading.h"

namespace montecl {

RayTracer::RayTracer(StageProgram& program, const Bvh& bvh, const Scene* scene, const SceneTextures* textures)
    : cl_(program.session()),
      lanes_(program.lanes()),
      intersect_(cl_.kernel(stageName(Stage::intersect))),
      intersectShadow_(cl_.kernel(stageName(Stage::intersect_shadow))) {
  const bool alpha = scene && anyAlphaTested(scene->materials, textures);
  frame_.textureCount = alpha && textures ? std::uint32_t(textures->textures.size()) : 0u;
  frame_.alphaTested = alpha ? 1u : 0u;
  bindings_.frame = {cl_.upload(std::vector<FrameParams>{frame_})};
  bindings_.nodes = {program.uploadNodes(bvh)};
  bindings_.tris = {cl_.upload(alpha ? alphaFlaggedTriangles(bvh.triangles, scene->materials, textures) : bvh.triangles)};
  // What the alpha test reads (1-entry dummies without cut-outs).
  bindings_.materials = {cl_.upload(alpha ? deviceMaterials(scene->materials, textures) : std::vector<Material>(1))};
  bindings_.shading = {cl_.upload(alpha ? buildTriangleShading(scene->triangles, bvh) : std::vector<TriangleShading>(1))};
  const bool textured = alpha && textures && !textures->textures.empty();
  bindings_.textures = {cl_.upload(textured ? textures->textures : std::vector<TextureDesc>(1))};
  bindings_.textureLevels = {cl_.upload(textured ? textures->levels : std::vector<TextureLevel>(1))};
  bindings_.texels = {cl_.upload(textured ? textures->texels : std::vector<std::uint16_t>(4))};
  bindings_.vertexColors = {cl_.upload(std::vector<float4>(1))};  // no albedo is read here
  bindings_.nanRays = {cl_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE)};
}

void RayTracer::setPacketAllRays(bool on) {
  frame_.packetAllRays = on ? 1u : 0u;
  bindings_.frame = {cl_.upload(std::vector<FrameParams>{frame_})};
}

void RayTracer::run(Stage stage, std::size_t n, int runs, std::vector<double>* kernelMs) {
  cl::Kernel& k = stage == Stage::intersect ? intersect_ : intersectShadow_;
  bindStageArgs(k, stage, bindings_);
  if (stageRunsPackets(stage)) n = (n + lanes_ - 1) / lanes_;  // W items per work item (lanes.h)
  for (int r = 0; r < std::max(1, runs); ++r) {
    if (kernelMs)
      kernelMs->push_back(cl_.launchTimed(k, n));
    else
      cl_.launch(k, n);
  }
}

std::vector<Hit> RayTracer::closest(const std::vector<Ray>& rays, int runs, std::vector<double>* kernelMs) {
  std::vector<Hit> hits(rays.size());
  if (rays.empty()) return hits;
  bindings_.rays = {cl_.upload(rays)};
  bindings_.rayCount = {cl_.upload(std::vector<cl_uint>{cl_uint(rays.size())})};
  bindings_.hits = {cl_.buffer<Hit>(rays.size())};
  run(Stage::intersect, rays.size(), runs, kernelMs);
  cl_.queue().enqueueReadBuffer(bindings_.hits.buffer, CL_TRUE, 0, hits.size() * sizeof(Hit), hits.data());
  return hits;
}

std::vector<int> RayTracer::occluded(const std::vector<Ray>& rays, int runs, std::vector<double>* kernelMs) {
  std::vector<int> result(rays.size());
  if (rays.empty()) return result;
  // Query k writes 1 to slot k when unblocked; slots start at 0.
  std::vector<ShadowWork> work(rays.size());
  for (std::size_t k = 0; k < rays.size(); ++k) {
    work[k].ray = rays[k];
    work[k].r = work[k].g = work[k].b = 1.0f;
    work[k].slot = cl_uint(k);
  }
  std::vector<cl_float4> contrib(rays.size(), cl_float4{{0.0f, 0.0f, 0.0f, 0.0f}});
  bindings_.queue = {cl_.upload(work)};
  bindings_.queueCount = {cl_.upload(std::vector<cl_uint>{cl_uint(rays.size())})};
  bindings_.shadowContrib = {cl_.upload(contrib, CL_MEM_READ_WRITE)};
  run(Stage::intersect_shadow, rays.size(), runs, kernelMs);
  cl_.queue().enqueueReadBuffer(bindings_.shadowContrib.buffer, CL_TRUE, 0, contrib.size() * sizeof(cl_float4),
                                contrib.data());
  for (std::size_t k = 0; k < rays.size(); ++k) result[k] = contrib[k].s[0] == 1.0f ? 0 : 1;
  return result;
}

std::uint32_t RayTracer::nanRays() {
  cl_uint n = 0;
  cl_.queue().enqueueReadBuffer(bindings_.nanRays.buffer, CL_TRUE, 0, sizeof(cl_uint), &n);
  return n;
}

}  // namespace montecl
