// shade_path: one bounce of the path tracer for each live path k < *rayCount (its ray rays[k],
// hit hits[k], id pathIds[k], the identity at bounce 0). Reads and writes the path's state by id:
// radiance[id] (accumulated L) and throughput[id] (rgb: the path weight; w: solid-angle pdf of the
// BSDF sample that made the ray, 0 for camera rays and after a delta lobe: no MIS). Adds emission seen (MIS-weighted against
// light sampling after a BSDF bounce) or the miss radiance (path_miss), pushes lightSamples
// next-event queries onto the shadow queue (slots id * shadowSlots + k, contributions MIS
// weighted but for delta lights; lights: emitter triangles, the environment and the light records,
// stages/direct_light.h), samples the
// BSDF (surface_at, kernels/shared/surface.h: the material kind's BSDF around the shading frame;
// textures filtered with the camera's ray-cone width at this segment's length, a lower bound after
// diffuse bounces), applies Russian roulette from depth
// rrDepth, and pushes the continuation ray onto nextRays / nextPathIds (compacted, *nextCount).
// Depth (Mitsuba's convention, FrameParams::maxDepth D): hit b adds emission when b < D, next-event
// estimation and a continuation when b + 1 < D; D = -1 is unlimited. Random numbers: bounce b
// owns dimension groups MCL_DIM_PATH + b * MCL_DIM_PATH_STRIDE + j (rng.h).
#pragma once
#include "direct_light.h"

// Radiance a path ray escaping the scene along dir brings back, before the path weight: the
// environment (camera rays see it unweighted; after a BSDF bounce it is MIS weighted against
// environment sampling with the BSDF sample's pdf lastPdf), else the background for camera rays
// and nothing afterwards.
MCL_INLINE float3 path_miss(MCL_CONSTANT const FrameParams* f, LightScene lights, LightHit miss, uint bounce,
                            float lastPdf) {
  if (!env_present(f)) return bounce == 0 ? xyz(f->background) : make_float3(0.0f, 0.0f, 0.0f);
  float3 le = light_eval(f, lights, miss);
  if (bounce == 0 || !(lastPdf > 0.0f)) return le;
  return le * power_heuristic(1.0f, lastPdf, (float)f->lightSamples, light_pdf(f, lights, miss));
}

MCL_INLINE uint path_dim(uint bounce, uint j) { return MCL_DIM_PATH + bounce * MCL_DIM_PATH_STRIDE + j; }

MCL_INLINE float max_component(float3 c) { return fmax(c.x, fmax(c.y, c.z)); }

// Light sample s (random numbers u) of next-event estimation at surface surf of path id (weight
// beta; wo toward the viewer, origin the offset hit point): pushes its occlusion query to slot
// id * shadowSlots + s, or nothing. The scalar body and the packet body's lanes of other kinds
// take their light samples here.
MCL_INLINE void path_light_sample(const shade_path_args* a, LightScene lights, Surface surf, float3 wo, float3 origin,
                                  float3 beta, uint id, uint s, float4 u) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  SurfaceFrame sf = surf.frame;
  Bsdf bsdf = surf.bsdf;
  float nLight = (float)f->lightSamples;
  LightSample ls = sample_direct_light(f, lights, origin, u);
  if (!(ls.pdf > 0.0f)) return;
  float3 fcos = bsdf_eval(bsdf, sf, wo, ls.wi);
  if (!(max_component(fcos) > 0.0f)) return;
  // A delta light: no BSDF sample can reach it, so no MIS weight.
  float weight = ls.delta ? 1.0f : power_heuristic(nLight, ls.pdf, 1.0f, bsdf_pdf(bsdf, sf, wo, ls.wi));
  float3 c = beta * fcos * ls.le * (weight / (ls.pdf * nLight));
  // A light below the geometric surface (seen through a transmitting lobe): the shadow ray
  // leaves from the far side, as a transmitted BSDF ray does.
  int above = above_surface(sf.ng, ls.wi);
  float3 from = above ? origin : bsdf_ray_origin(sf.p, sf.ng, MCL_BSDF_TRANSMISSION, f->offsetScale);
  float tmaxFrom;
  float3 dirFrom = shadow_dir_from(origin, from, ls.wi, ls.tmax, &tmaxFrom);
  push_shadow_query(a->queue, a->queueCount, from, above ? ls.wi : dirFrom, above ? ls.tmax : tmaxFrom, c,
                    id * f->shadowSlots + s);
}

// The path's continuation from surface surf (random numbers u: x, y the BSDF sample, z roulette,
// w the lobe): samples the BSDF, applies Russian roulette from depth rrDepth and pushes the ray onto
// nextRays / nextPathIds with the new throughput, or ends the path.
MCL_INLINE void path_continue(const shade_path_args* a, Surface surf, float3 wo, float3 origin, float3 beta, uint id,
                              float4 u) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  SurfaceFrame sf = surf.frame;
  BsdfSample bs = bsdf_sample(surf.bsdf, sf, wo, u.x, u.y, u.w);
  float3 wi = bs.wi;
  float pdf = bs.pdf;
  float3 next = beta * bs.weight;
  if (!(pdf > 0.0f)) return;
  if (a->pathBounce + 1u >= f->rrDepth) {  // Russian roulette (depth after this bounce: bounce + 1)
    float q = fmin(0.95f, max_component(next));
    if (!(u.z < q)) return;
    next = next / q;
  }
  if (!(max_component(next) > 0.0f)) return;
  a->throughput[id] = with_w(next, (bs.flags & MCL_BSDF_DELTA) ? 0.0f : pdf);  // w 0: no MIS at the next hit
  uint slot = MCL_ATOMIC_INC(a->nextCount);
  Ray r;
  r.origin = with_w((bs.flags & MCL_BSDF_TRANSMISSION) ? bsdf_ray_origin(sf.p, sf.ng, bs.flags, f->offsetScale) : origin,
                    0.0f);
  r.dir = with_w(wi, INFINITY);
  a->nextRays[slot] = r;
  a->nextPathIds[slot] = id;
}

// Whether light samples are taken at surface surf: some light exists and the BSDF is not purely
// delta (every light direction has f = 0 there; the emitter its BSDF sample finds counts fully).
MCL_INLINE int path_takes_light_samples(MCL_CONSTANT const FrameParams* f, Surface surf) {
  return (f->emitterCount > 0 || env_present(f) || f->lightCount > 0) && !bsdf_is_delta(surf.bsdf);
}

MCL_INLINE void shade_path_item(const shade_path_args* a, uint k) {
  if (k >= *a->rayCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  uint bounce = a->pathBounce;
  uint id = bounce == 0 ? k : a->pathIds[k];
  for (uint s = 0; s < f->shadowSlots; ++s)
    a->shadowContrib[id * f->shadowSlots + s] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 beta4 = bounce == 0 ? make_float4(1.0f, 1.0f, 1.0f, 0.0f) : a->throughput[id];
  float3 beta = xyz(beta4);
  float3 L = bounce == 0 ? make_float3(0.0f, 0.0f, 0.0f) : xyz(a->radiance[id]);
  Hit h = a->hits[k];
  float3 dir = xyz(a->rays[k].dir);
  LightScene lights = make_light_scene(a->tris, a->normals, a->materials, a->emitters, a->envMap, a->envCdf, a->lightRecords,
                                       a->shading, make_texture_tables(a->textures, a->textureLevels, a->texels));
  LightHit lh = light_hit(h, dir);  // the environment on a miss, else the hit triangle
  if (h.tri == MCL_NO_HIT) {
    a->radiance[id] = with_w(L + beta * path_miss(f, lights, lh, bounce, beta4.w), 0.0f);
    return;
  }
  float nLight = (float)f->lightSamples;
  float3 le = light_eval(f, lights, lh);
  if (le.x > 0.0f || le.y > 0.0f || le.z > 0.0f) {
    float weight = 1.0f;
    if (bounce > 0 && beta4.w > 0.0f && f->emitterCount > 0)  // a BSDF sample found an emitter
      weight = power_heuristic(1.0f, beta4.w, nLight, light_pdf(f, lights, lh));
    L += beta * le * weight;
  }
  a->radiance[id] = with_w(L, 0.0f);
  if (!(f->maxDepth < 0 || (int)bounce + 1 < f->maxDepth)) return;

  uint pixel = item_pixel(f, a->active, a->waveStart, id), sample = item_sample(f, a->waveStart, id);
  Surface surf = surface_at(MCL_STAGE_SURFACE_SCENE(a), f, h, hit_instance(f, a->hitInstances, k), dir,
                            sample_ref(pixel, sample, bounce));
  float3 wo = dir * -1.0f;
  float3 origin = offset_ray_origin(surf.frame.p, surf.frame.ng, f->offsetScale);
  for (uint s = 0; path_takes_light_samples(f, surf) && s < f->lightSamples; ++s)
    path_light_sample(a, lights, surf, wo, origin, beta, id, s, sample_uniform4(f, pixel, sample, path_dim(bounce, 1u + s)));
  path_continue(a, surf, wo, origin, beta, id, sample_uniform4(f, pixel, sample, path_dim(bounce, 0u)));  // z: roulette, w: lobe
}
