// ray_tracer.h: traces arbitrary batches of rays through the device's intersect (closest hit) and
// intersect_shadow (any hit) kernels, for tests and benchmarks of the traversal on its own.
#pragma once
#include <vector>

#include "bvh/bvh.h"
#include "cl/cl_session.h"

namespace montecl {

class RayTracer {
 public:
  RayTracer(ClSession& session, const Bvh& bvh);

  // Closest hit of each ray (dir.w = tmax).
  std::vector<Hit> closest(const std::vector<Ray>& rays);
  // 1 where something blocks the ray before dir.w, else 0.
  std::vector<int> occluded(const std::vector<Ray>& rays);

 private:
  ClSession& cl_;
  cl::Buffer nodes_, tris_;
  cl::Kernel intersect_, intersectShadow_;
};

}  // namespace montecl
