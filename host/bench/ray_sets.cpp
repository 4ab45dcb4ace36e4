// ray_sets.cpp: seeded primary / AO / shadow / diffuse-bounce ray generation for the bench (same camera, RNG,
// hemisphere sampling, facing normal, origin offset, emitter table and light sampling as the
// render stages) and the parallel host reference traversal of every ray.
#include "bench/ray_sets.h"

#include <algorithm>
#include <cmath>
#include <chrono>

#include "kernels/shared/camera.h"
#include "kernels/shared/lights.h"
#include "kernels/stages/stage_common.h"
#include "render/emitters.h"
#include "render/frame_params.h"
#include "util/parallel_for.h"

namespace montecl {

namespace {

// Geometric normal of a hit triangle, flipped to face the incoming direction: what the stages'
// surface_frame gives (its ng) without the precomputed normals buffer, with the same functions.
float3 facing_normal(const Triangle* tri, float3 incoming) {
  return orient_facing(triangle_unit_normal(xyz(tri->e1), xyz(tri->e2)), incoming);
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void referenceClosest(const Bvh& bvh, RaySet& set, unsigned threads, BvhLayout layout, const AlphaScene* alpha) {
  set.refT.assign(set.rays.size(), INFINITY);
  auto t0 = std::chrono::steady_clock::now();
  parallelChunks(set.rays.size(), threads, kRayGrain, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Ray& r = set.rays[i];
      Hit h = intersectClosest(bvh, xyz(r.origin), xyz(r.dir), r.dir.w, layout, alpha);
      set.refT[i] = h.tri == MCL_NO_HIT ? INFINITY : h.t;
    }
  }, kRayGrain);
  set.refMs = msSince(t0);
}

void referenceAny(const Bvh& bvh, RaySet& set, unsigned threads, BvhLayout layout, const AlphaScene* alpha) {
  set.refOccluded.assign(set.rays.size(), 0);
  auto t0 = std::chrono::steady_clock::now();
  parallelChunks(set.rays.size(), threads, kRayGrain, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Ray& r = set.rays[i];
      set.refOccluded[i] = intersectAny(bvh, xyz(r.origin), xyz(r.dir), r.dir.w, layout, alpha) ? 1 : 0;
    }
  }, kRayGrain);
  set.refMs = msSince(t0);
}

}  // namespace

RaySets makeRaySets(const Scene& scene, const Bvh& bvh, unsigned threads, BvhLayout layout, const AlphaScene* alpha) {
  RaySets s;
  s.primary.kind = "primary";
  s.ao.kind = "ao";
  s.ao.query = RayKind::Any;
  s.shadow.kind = "shadow";
  s.shadow.query = RayKind::Any;
  s.bounce.kind = "bounce";
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
  parallelChunks(pixels, threads, kRayGrain, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Ray& r = s.primary.rays[i];
      s.primaryHits[i] = intersectClosest(bvh, xyz(r.origin), xyz(r.dir), r.dir.w, layout, alpha);
    }
  }, kRayGrain);
  s.primary.refMs = msSince(t0);
  s.primary.refT.resize(pixels);
  for (uint p = 0; p < pixels; ++p) s.primary.refT[p] = s.primaryHits[p].t;

  // Emitters: the renderer's table (BVH order, weighted by area * luminance(Ke)).
  const EmitterTable lights = buildEmitterTable(bvh, scene.materials);
  const uint emitterCount = uint(lights.emitters.size());
  s.emitters = emitterCount;

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
    for (uint k = 0; k < kBounceRaysPerHit; ++k) {
      float4 u = rng_uniform4(seed, p, k, 3u);  // a group of its own: AO's directions would repeat
      Ray r;
      r.origin = with_w(org, 0.0f);
      r.dir = with_w(to_world(sample_cosine_hemisphere(u.x, u.y), n), INFINITY);
      s.bounce.rays.push_back(r);
    }
    if (emitterCount == 0) continue;
    // The first light sample of the direct integrator's sample 0 (stage_shade_direct in
    // kernels/shared/stages_direct.h): same emitter pick, point, skip rule and shortened tmax.
    float4 u = rng_uniform4(seed, p, 0, MCL_DIM_LIGHT);
    const Emitter& em = lights.emitters[pick_emitter(lights.emitters.data(), emitterCount, u.x)];
    const Triangle* lt = &bvh.triangles[em.tri];
    float3 target = sample_triangle(xyz(lt->v0), xyz(lt->e1), xyz(lt->e2), u.y, u.z);
    float3 toLight = target - org;
    float dist = sqrt(dot(toLight, toLight));
    float3 wi = toLight / dist;
    float cosLight = -dot(normalize(cross(xyz(lt->e1), xyz(lt->e2))), wi);
    if (!(cosLight > 0.0f && dot(n, wi) > 0.0f && dist > 0.0f)) continue;
    Ray r;
    r.origin = with_w(org, 0.0f);
    r.dir = with_w(wi, dist * (1.0f - 1e-4f));  // stop short of the emitter, as the stage does
    s.shadow.rays.push_back(r);
  }
  referenceAny(bvh, s.ao, threads, layout, alpha);
  referenceAny(bvh, s.shadow, threads, layout, alpha);
  referenceClosest(bvh, s.bounce, threads, layout, alpha);
  return s;
}

}  // namespace montecl
