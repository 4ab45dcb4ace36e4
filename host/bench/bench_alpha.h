// bench_alpha.h: the alpha-tested triangles of a bench scene (cut-outs, stochastic transparency),
// so that every tracer of `montecl bench` (the device kernels, the host reference, Embree through
// its filter functions) applies the same alpha test as renders. Reads the scene and its textures;
// flags the BVH's alpha-tested triangles.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "kernels/shared/surface_texture.h"
#include "scene/scene.h"
#include "texture/scene_textures.h"

namespace montecl {

struct BenchAlpha {
  const Scene* scene = nullptr;
  SceneTextures textures;
  std::vector<Material> materials;           // device materials: alpha texture, cutoff, channel
  std::vector<TriangleShading> shading;      // BVH order (UVs)
  std::vector<std::uint8_t> tested;          // per input triangle: its material is alpha-tested
  std::size_t testedCount = 0;
  std::vector<std::uint32_t> slot;           // per input triangle: its canonical slot in the BVH
  const Triangle* tris = nullptr;            // the BVH's triangles, flagged
  AlphaScene host{};                         // host pointers into the above (intersectClosest/Any)

  // The alpha test of input triangle tri at barycentrics (u, v) of v1 and v2, hit by the ray
  // org + t dir (Embree's filter): the renders' own test (alpha_hit_exists) on its BVH slot.
  bool exists(std::uint32_t tri, float u, float v, const float3& org, const float3& dir) const;
};

// Null when no material is alpha-tested (then nothing changes). Otherwise loads the textures
// (automatic budget; warnings appended), flags bvh.triangles (MCL_ATTR_ALPHA) and fills the rest.
std::unique_ptr<BenchAlpha> makeBenchAlpha(const Scene& scene, Bvh& bvh, std::vector<std::string>& warnings);

}  // namespace montecl
