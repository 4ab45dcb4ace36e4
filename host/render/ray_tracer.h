// ray_tracer.h: traces arbitrary batches of rays through the stage program's intersect (closest
// hit) and intersect_shadow (any hit) kernels, for tests and benchmarks of the traversal on its own.
#pragma once
#include <vector>

#include "bvh/bvh.h"
#include "render/stage_bindings.h"
#include "render/stage_program.h"
#include "texture/scene_textures.h"

namespace montecl {

class RayTracer {
 public:
  // With a scene and its textures, hits on cut-outs whose alpha is below the cutoff do not exist
  // (as in renders); without, every triangle is opaque.
  RayTracer(StageProgram& program, const Bvh& bvh, const Scene* scene = nullptr,
            const SceneTextures* textures = nullptr);

  // Closest hit of each ray (dir.w = tmax). With kernelMs (the session must profile), the kernel
  // runs `runs` times and each run's execution time is appended (benchmarks).
  std::vector<Hit> closest(const std::vector<Ray>& rays, int runs = 1, std::vector<double>* kernelMs = nullptr);
  // 1 where something blocks the ray before dir.w, else 0; runs and kernelMs as above.
  std::vector<int> occluded(const std::vector<Ray>& rays, int runs = 1, std::vector<double>* kernelMs = nullptr);
  // Rays with a NaN/inf origin or direction met so far (every run counts; they are misses, and a
  // non-finite occlusion query is reported occluded: its light is dropped).
  std::uint32_t nanRays();
  // Whether rays in any octants take the packet traversals (FrameParams::packetAllRays, as renders
  // of small trees set it); off by default, where only packets of rays in one octant do.
  void setPacketAllRays(bool on);

 private:
  void run(Stage stage, std::size_t n, int runs, std::vector<double>* kernelMs);

  ClSession& cl_;
  unsigned lanes_;  // the program's W: a packet stage's work item traces W consecutive rays
  FrameParams frame_{};
  ClBindings bindings_;  // frame (unused by the traversal stages), nodes and tris; the rest per call
  cl::Kernel intersect_, intersectShadow_;
};

}  // namespace montecl
