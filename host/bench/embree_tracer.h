// embree_tracer.h: the bench's comparison point: the same triangles built with Embree 3
// (RTC_BUILD_QUALITY_HIGH) and the same rays traced with rtcIntersect1 / rtcOccluded1 on T
// std::threads. Compiled to a stub (available() == false) when Embree was not found at configure.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "kernels/shared/types.h"
#include "scene/scene.h"

namespace montecl {

class EmbreeTracer {
 public:
  // Whether a hit at barycentrics (u, v) of input triangle tri by the ray org + t dir exists (the
  // alpha test of cut-outs and stochastic transparency).
  using AlphaTest = std::function<bool(std::uint32_t tri, float u, float v, const float3& org, const float3& dir)>;

  // Builds the scene on `threads` threads; buildMs() is the time of rtcCommitScene (after one
  // warm-up build that starts Embree's thread pool). With alphaTest, the triangles where
  // alphaTested[i] is set form a second geometry whose intersection and occlusion filter
  // functions reject the hits alphaTest refuses (the others stay filter-free).
  EmbreeTracer(const std::vector<SceneTriangle>& tris, unsigned threads, AlphaTest alphaTest = {},
               const std::vector<std::uint8_t>& alphaTested = {});
  ~EmbreeTracer();
  EmbreeTracer(const EmbreeTracer&) = delete;
  EmbreeTracer& operator=(const EmbreeTracer&) = delete;

  static bool available();
  static std::string version();
  double buildMs() const { return buildMs_; }

  // Traces every ray once on `threads` threads; returns the wall time in ms. Results: closest
  // hit t (INFINITY on a miss), or occluded 0 / 1.
  double closest(const std::vector<Ray>& rays, std::vector<float>& t) const;
  double occluded(const std::vector<Ray>& rays, std::vector<std::uint8_t>& occ) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  unsigned threads_;
  double buildMs_ = 0.0;
};

}  // namespace montecl
