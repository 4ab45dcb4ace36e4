// ray_sets.h: the fixed, seeded ray sets of `montecl bench` (primary, ambient occlusion, shadow,
// diffuse bounce),
// built on the host with the kernels' own camera, RNG, sampling and offset code, plus a parallel
// host reference traversal (intersectClosest / intersectAny) to check every result against.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "scene/scene.h"

namespace montecl {

constexpr int kAoRaysPerHit = 8;
// Diffuse bounce: closest-hit continuation rays of a path tracer, this many per primary hit.
constexpr int kBounceRaysPerHit = 4;
// The host references and Embree trace rays in chunks of this many, handed out dynamically
// (parallelChunks' grain: a ray's cost varies).
constexpr std::size_t kRayGrain = 1024;

enum class RayKind { Closest, Any };  // traced by `intersect` / `intersect_shadow`

struct RaySet {
  std::string kind;           // "primary", "ao", "shadow", "bounce"
  RayKind query = RayKind::Closest;
  std::vector<Ray> rays;      // dir.w = tmax
  // Host reference: closest hit t (INFINITY on a miss) or occluded (0 / 1) for each ray.
  std::vector<float> refT;
  std::vector<std::uint8_t> refOccluded;
  double refMs = 0.0;         // wall time of the host reference traversal (for host Mrays/s)
};

struct RaySets {
  RaySet primary, ao, shadow;  // shadow.rays is empty when the scene has no emitters
  RaySet bounce;               // "diffuse bounce": incoherent closest-hit secondary rays
  std::vector<Hit> primaryHits;  // host reference closest hits of the primary rays
  std::size_t emitters = 0;      // emitting triangles (render/emitters.h: area * luminance(Ke) > 0)
};

// Primary rays: one per pixel of scene.camera, jittered with the camera RNG dimension of sample 0
// (seed = scene.render.seed). AO: kAoRaysPerHit cosine-distributed rays per primary hit, tmax =
// scene.render.aoDistance. Shadow: per primary hit, the shadow ray of the direct integrator's
// first light sample of sample 0 (emitter picked by area * luminance, uniform point on it, none
// when the light or the surface faces away), stopping just short of the light. References
// Diffuse bounce: kBounceRaysPerHit cosine-distributed rays per primary hit about the facing
// normal (RNG dimension group 3, so not the AO rays' directions), unbounded, traced closest-hit: the
// continuation rays that dominate path tracing. References
// computed on `threads` threads with the host traversal of `layout` (the one the device runs).
// With alpha, the references apply the cut-outs' alpha test (bvh.triangles flagged).
RaySets makeRaySets(const Scene& scene, const Bvh& bvh, unsigned threads,
                    BvhLayout layout = BvhLayout::Wide, const AlphaScene* alpha = nullptr);

}  // namespace montecl
