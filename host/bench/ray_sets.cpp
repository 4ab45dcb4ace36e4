// ray_sets.cpp: seeded primary / AO / shadow ray generation for the bench (same camera, RNG,
// hemisphere sampling, facing normal and origin offset as the render stages) and the parallel
// host reference traversal of every ray.
#include "bench/ray_sets.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <thread>

#include "kernels/shared/camera.h"
#include "kernels/stages/stage_common.h"
#include "render/frame_params.h"

namespace montecl {

void parallelFor(std::size_t n, unsigned threads, const std::function<void(std::size_t, std::size_t)>& body) {
  threads = std::max(1u, threads);
  const std::size_t chunk = 1024;
  std::atomic<std::size_t> next{0};
  auto worker = [&]() {
    for (;;) {
      std::size_t b = next.fetch_add(chunk);
      if (b >= n) return;
      body(b, std::min(n, b + chunk));
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void referenceAny(const Bvh& bvh, RaySet& set, unsigned threads, BvhLayout layout) {
  set.refOccluded.assign(set.rays.size(), 0);
  auto t0 = std::chrono::steady_clock::now();
  parallelFor(set.rays.size(), threads, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Ray& r = set.rays[i];
      set.refOccluded[i] = intersectAny(bvh, xyz(r.origin), xyz(r.dir), r.dir.w, layout) ? 1 : 0;
    }
  });
  set.refMs = msSince(t0);
}

}  // namespace

RaySets makeRaySets(const Scene& scene, const Bvh& bvh, unsigned threads, BvhLayout layout) {
  RaySets s;
  s.primary.kind = "primary";
  s.ao.kind = "ao";
  s.ao.query = RayKind::Any;
  s.shadow.kind = "shadow";
  s.shadow.query = RayKind::Any;
  const uint seed = scene.render.seed;
  const FrameParams f = makeFrameParams(scene.camera, scene.render, 1);
  const uint width = f.width, pixels = f.width * f.height;

  // Primary rays and their reference hits.
  s.primary.rays.resize(pixels);
  for (uint p = 0; p < pixels; ++p) {
    float4 u = rng_uniform4(seed, p, 0, MCL_DIM_CAMERA);
    s.primary.rays[p] = camera_ray(&f, float(p % width) + u.x, float(p / width) + u.y);
  }
  s.primaryHits.resize(pixels);
  auto t0 = std::chrono::steady_clock::now();
  parallelFor(pixels, threads, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Ray& r = s.primary.rays[i];
      s.primaryHits[i] = intersectClosest(bvh, xyz(r.origin), xyz(r.dir), r.dir.w, layout);
    }
  });
  s.primary.refMs = msSince(t0);
  s.primary.refT.resize(pixels);
  for (uint p = 0; p < pixels; ++p) s.primary.refT[p] = s.primaryHits[p].t;

  // Emitters (BVH order, so sampled points lie on the very triangles the kernels see), with an
  // area CDF for choosing one.
  std::vector<uint> emitters;
  std::vector<double> cdf;
  double area = 0.0;
  for (uint i = 0; i < bvh.triangles.size(); ++i) {
    uint input = bvh.order[i];
    const MaterialDesc& m = scene.materials[scene.triangles[input].material];
    if (m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f) {
      const Triangle& t = bvh.triangles[i];
      area += 0.5 * glm::length(glm::cross(xyz(t.e1), xyz(t.e2)));
      emitters.push_back(i);
      cdf.push_back(area);
    }
  }
  s.emitters = emitters.size();

  const float offsetScale = offsetScaleFor(scene.triangles);  // as the renderer's FrameParams
  for (uint p = 0; p < pixels; ++p) {
    const Hit& h = s.primaryHits[p];
    if (h.tri == MCL_NO_HIT) continue;
    const Triangle* tri = &bvh.triangles[h.tri];
    float3 n = facing_normal(tri, xyz(s.primary.rays[p].dir));
    float3 org = offset_ray_origin(hit_position(tri, h), n, offsetScale);
    for (uint k = 0; k < kAoRaysPerHit; ++k) {
      float4 u = rng_uniform4(seed, p, k, MCL_DIM_AO);
      Ray r;
      r.origin = with_w(org, 0.0f);
      r.dir = with_w(to_world(sample_cosine_hemisphere(u.x, u.y), n), scene.render.aoDistance);
      s.ao.rays.push_back(r);
    }
    if (emitters.empty()) continue;
    float4 u = rng_uniform4(seed, p, 0, MCL_DIM_LIGHT);
    double pick = double(u.x) * area;
    std::size_t e = std::min<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin(),
                                          emitters.size() - 1);
    const Triangle& lt = bvh.triangles[emitters[e]];
    float su = std::sqrt(u.y);  // uniform point on the triangle
    float3 target = xyz(lt.v0) + xyz(lt.e1) * (su * (1.0f - u.z)) + xyz(lt.e2) * (su * u.z);
    float3 d = target - org;
    float dist = glm::length(d);
    if (!(dist > 1e-6f)) continue;
    Ray r;
    r.origin = with_w(org, 0.0f);
    r.dir = with_w(d / dist, dist * (1.0f - 1e-3f));  // stop short of the emitter itself
    s.shadow.rays.push_back(r);
  }
  referenceAny(bvh, s.ao, threads, layout);
  referenceAny(bvh, s.shadow, threads, layout);
  return s;
}

}  // namespace montecl
