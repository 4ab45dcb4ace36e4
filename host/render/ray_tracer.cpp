// ray_tracer.cpp: one-shot launches of the intersect and intersect_shadow kernels.
#include "render/ray_tracer.h"

#include <algorithm>

#include "render/bvh_buffer.h"

namespace montecl {

RayTracer::RayTracer(ClSession& session, const Bvh& bvh)
    : cl_(session), nodes_(uploadBvhNodes(session, bvh)), tris_(session.upload(bvh.triangles)),
      intersect_(session.kernel("intersect")), intersectShadow_(session.kernel("intersect_shadow")) {}

void RayTracer::run(cl::Kernel& k, std::size_t n, int runs, std::vector<double>* kernelMs) {
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
  cl::Buffer rayBuf = cl_.upload(rays);
  cl::Buffer count = cl_.upload(std::vector<cl_uint>{cl_uint(rays.size())});
  cl::Buffer hitBuf = cl_.buffer<Hit>(rays.size());
  setArgs(intersect_, nodes_, tris_, rayBuf, count, hitBuf);
  run(intersect_, rays.size(), runs, kernelMs);
  cl_.queue().enqueueReadBuffer(hitBuf, CL_TRUE, 0, hits.size() * sizeof(Hit), hits.data());
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
  cl::Buffer workBuf = cl_.upload(work);
  cl::Buffer count = cl_.upload(std::vector<cl_uint>{cl_uint(rays.size())});
  std::vector<cl_float4> contrib(rays.size(), cl_float4{{0.0f, 0.0f, 0.0f, 0.0f}});
  cl::Buffer contribBuf = cl_.upload(contrib, CL_MEM_READ_WRITE);
  setArgs(intersectShadow_, nodes_, tris_, workBuf, count, contribBuf);
  run(intersectShadow_, rays.size(), runs, kernelMs);
  cl_.queue().enqueueReadBuffer(contribBuf, CL_TRUE, 0, contrib.size() * sizeof(cl_float4), contrib.data());
  for (std::size_t k = 0; k < rays.size(); ++k) result[k] = contrib[k].s[0] == 1.0f ? 0 : 1;
  return result;
}

}  // namespace montecl
