// stages.h: the body of every wavefront stage for one work item, shared by the OpenCL kernels
// (kernels/*.cl are thin wrappers) and the host. A wave holds `waveCount` consecutive indices
// g = waveStart + i into the active-pixel list, sample-major: pixel = active[g % activeCount],
// sample = g / activeCount, so a pixel's samples are always accumulated in sample order whatever
// the wave size. Without adaptive sampling the list holds every pixel in order.
#pragma once
#include "camera.h"
#include "rng.h"
#include "sampling.h"
#include "traverse.h"

// The pixel and the sample index of wave item i.
MCL_INLINE uint item_pixel(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                           ulong waveStart, uint i) {
  return active[(uint)((waveStart + i) % f->activeCount)];
}
MCL_INLINE uint item_sample(MCL_CONSTANT const FrameParams* f, ulong waveStart, uint i) {
  return (uint)((waveStart + i) / f->activeCount);
}

// generate: writes the camera ray of item i.
MCL_INLINE void stage_generate(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                               ulong waveStart, uint i, MCL_GLOBAL Ray* rays) {
  uint pixel = item_pixel(f, active, waveStart, i);
  uint sample = item_sample(f, waveStart, i);
  float4 u = rng_uniform4(f->seed, pixel, sample, MCL_DIM_CAMERA);
  float px = (float)(pixel % f->width) + u.x;
  float py = (float)(pixel / f->width) + u.y;
  rays[i] = camera_ray(f, px, py);
}

// intersect: closest hit of ray i.
MCL_INLINE void stage_intersect(MCL_GLOBAL const BvhTraversalNode* nodes, MCL_GLOBAL const Triangle* tris,
                                MCL_GLOBAL const Ray* rays, uint i, MCL_GLOBAL Hit* hits) {
  Ray r = rays[i];
  hits[i] = bvh_closest_hit(nodes, tris, xyz(r.origin), xyz(r.dir), r.dir.w);
}

// Geometric normal of a hit triangle, flipped to face the incoming direction.
MCL_INLINE float3 facing_normal(MCL_GLOBAL const Triangle* tri, float3 incoming) {
  float3 n = normalize(cross(xyz(tri->e1), xyz(tri->e2)));
  return dot(n, incoming) > 0.0f ? -n : n;
}

// Hit position from barycentrics (more accurate than org + t * dir).
MCL_INLINE float3 hit_position(MCL_GLOBAL const Triangle* tri, Hit h) {
  return xyz(tri->v0) + xyz(tri->e1) * h.u + xyz(tri->e2) * h.v;
}

// shade_ao: for item i, writes radiance[i] (background on a miss, else 0), clears its shadow
// slots, and pushes one occlusion query whose unoccluded value is the AO estimate
// V cos(theta) / (pi p(w)): 1 for cosine sampling, 2 cos(theta) for uniform sampling.
MCL_INLINE void stage_shade_ao(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                               ulong waveStart,
                               MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const Ray* rays,
                               MCL_GLOBAL const Hit* hits, uint i, MCL_GLOBAL float4* radiance,
                               MCL_GLOBAL float4* shadowContrib, MCL_GLOBAL ShadowWork* queue,
                               MCL_GLOBAL volatile uint* queueCount) {
  Hit h = hits[i];
  for (uint k = 0; k < f->shadowSlots; ++k)
    shadowContrib[i * f->shadowSlots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  if (h.tri == MCL_NO_HIT) {
    radiance[i] = f->background;
    return;
  }
  radiance[i] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float3 dir = xyz(rays[i].dir);
  MCL_GLOBAL const Triangle* tri = &tris[h.tri];
  float3 n = facing_normal(tri, dir);
  float4 u = rng_uniform4(f->seed, item_pixel(f, active, waveStart, i), item_sample(f, waveStart, i),
                          MCL_DIM_AO);
  float3 dirLocal;
  float weight;
  if (f->aoSampling == MCL_AO_COSINE) {
    dirLocal = sample_cosine_hemisphere(u.x, u.y);
    weight = 1.0f;  // cos / (pi * cos / pi)
  } else {
    dirLocal = sample_uniform_hemisphere(u.x, u.y);
    weight = 2.0f * dirLocal.z;  // cos / (pi / (2 pi))
  }
  if (!(weight > 0.0f)) return;
  ShadowWork w;
  w.ray.origin = with_w(offset_ray_origin(hit_position(tri, h), n), 0.0f);
  w.ray.dir = with_w(to_world(dirLocal, n), f->aoDistance);
  w.r = weight;
  w.g = weight;
  w.b = weight;
  w.slot = i * f->shadowSlots;
  queue[MCL_ATOMIC_INC(queueCount)] = w;
}

// intersect_shadow: writes the query's contribution to its slot when nothing blocks the ray.
MCL_INLINE void stage_intersect_shadow(MCL_GLOBAL const BvhTraversalNode* nodes,
                                       MCL_GLOBAL const Triangle* tris,
                                       MCL_GLOBAL const ShadowWork* queue, uint k,
                                       MCL_GLOBAL float4* shadowContrib) {
  ShadowWork w = queue[k];
  if (!bvh_any_hit(nodes, tris, xyz(w.ray.origin), xyz(w.ray.dir), w.ray.dir.w))
    shadowContrib[w.slot] = make_float4(w.r, w.g, w.b, 0.0f);
}

// accumulate: for the j-th pixel touched by the wave, adds each of its samples in the wave, in
// sample order, to the pixel's running mean (rgb, w = sample count n) and M2 (rgb: sum of squared
// deviations from the mean), by Welford's update: no cancellation when the variance is small
// against the mean, however many samples.
MCL_INLINE void stage_accumulate(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                                 ulong waveStart, uint waveCount, uint j,
                                 MCL_GLOBAL const float4* radiance,
                                 MCL_GLOBAL const float4* shadowContrib, MCL_GLOBAL float4* mean,
                                 MCL_GLOBAL float4* m2) {
  uint pixel = item_pixel(f, active, waveStart, j);
  float4 m = mean[pixel];
  float4 q = m2[pixel];
  // float4 throughout (w lanes zeroed): no float3, whose padding lane simulators flag as undefined.
  for (uint i = j; i < waveCount; i += f->activeCount) {
    float4 value = radiance[i];
    for (uint k = 0; k < f->shadowSlots; ++k) value += shadowContrib[i * f->shadowSlots + k];
    value.w = 0.0f;
    float n = m.w + 1.0f;
    float4 delta = value - m;
    delta.w = 0.0f;
    float4 updated = m + delta / n;
    updated.w = n;
    float4 spread = delta * (value - updated);
    spread.w = 0.0f;
    m = updated;
    q += spread;
  }
  mean[pixel] = m;
  m2[pixel] = q;
}
