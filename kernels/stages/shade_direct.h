// shade_direct: reads camera rays, hits, materials, the emitter table, the environment, the
// attribute buffer and textures; for camera item i writes radiance[i] (on a miss the environment,
// or the background without one; else Le seen directly), pushes K light-sample occlusion queries
// onto the shadow queue (light / mis; lights: the environment, emitter triangles and the light
// records: point, spot, directional, the delta ones by light sampling only; stages/direct_light.h) and writes the BSDF ray bounce[i] (brdf / mis; otherwise an empty ray
// with tmax < 0). Surfaces: surface_at (shared/surface.h): the shading frame and the material
// kind's BSDF (shared/bsdf.h; light directions below the geometric surface count only through a
// transmitting lobe, their shadow rays leaving from the far side).
// Shadow slots per sample: [0, K) light samples, K the BSDF sample (shade_direct_hit); each
// strategy leaves the slots it does not use at 0.
#pragma once
#include "direct_light.h"

// Light sample k (random numbers u) at item i's surface surf (wo toward the camera, origin the
// offset hit point; useBrdf: MIS against the BSDF ray): pushes its occlusion query to slot
// i * shadowSlots + k, or nothing. The scalar body and the packet body's lanes of other kinds take
// their light samples here.
MCL_INLINE void direct_light_sample(const shade_direct_args* a, LightScene lights, Surface surf, float3 wo,
                                    float3 origin, int useBrdf, uint i, uint k, float4 u) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  SurfaceFrame sf = surf.frame;
  Bsdf bsdf = surf.bsdf;
  float nLight = (float)f->lightSamples;
  LightSample ls = sample_direct_light(f, lights, origin, u);
  float cosSurf = frame_cosine(sf, ls.wi);  // 0 below the geometric surface
  // A light below the geometric surface is seen through it (a transmitting lobe, e.g. rough
  // glass): the BSDF's own f |cos| (0 for a reflecting kind), the shadow ray from the far side.
  int below = !above_surface(sf.ng, ls.wi);
  float3 fcosBelow = below ? bsdf_eval(bsdf, sf, wo, ls.wi) : make_float3(0.0f, 0.0f, 0.0f);
  if (!(ls.pdf > 0.0f && (below ? fmax(fcosBelow.x, fmax(fcosBelow.y, fcosBelow.z)) > 0.0f : cosSurf > 0.0f))) return;
  // A delta light: no BSDF sample can reach it, so no MIS weight.
  float weight = useBrdf && !ls.delta ? power_heuristic(nLight, ls.pdf, 1.0f, bsdf_pdf(bsdf, sf, wo, ls.wi)) : 1.0f;
  float3 c = below ? fcosBelow * ls.le * (weight / (ls.pdf * nLight))
                   : bsdf_f(bsdf, sf, wo, ls.wi) * ls.le * (cosSurf * weight / (ls.pdf * nLight));
  float3 from = below ? bsdf_ray_origin(sf.p, sf.ng, MCL_BSDF_TRANSMISSION, f->offsetScale) : origin;
  float tmaxFrom;
  float3 dirFrom = shadow_dir_from(origin, from, ls.wi, ls.tmax, &tmaxFrom);
  push_shadow_query(a->queue, a->queueCount, from, below ? dirFrom : ls.wi, below ? tmaxFrom : ls.tmax, c,
                    i * f->shadowSlots + k);
}

// The BSDF ray at surface surf from random numbers u (weighed in shade_direct_hit): an empty ray
// (tmax < 0) where the sample is absorbed; a transmitted one starts below the surface.
MCL_INLINE Ray direct_bsdf_ray(MCL_CONSTANT const FrameParams* f, Surface surf, float3 wo, float3 origin, float4 u) {
  Ray bounce;
  bounce.origin = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  bounce.dir = make_float4(0.0f, 0.0f, 1.0f, -1.0f);
  BsdfDirection d = bsdf_sample_direction(surf.bsdf, surf.frame, wo, u.x, u.y, u.z);
  if (d.traced) {
    bounce.origin = with_w(
        (d.flags & MCL_BSDF_TRANSMISSION) ? bsdf_ray_origin(surf.frame.p, surf.frame.ng, d.flags, f->offsetScale) : origin,
        0.0f);
    bounce.dir = with_w(d.wi, INFINITY);
  }
  return bounce;
}

// Light sampling at a purely delta surface (a mirror, smooth glass) finds nothing (f = 0 for
// every light direction): skipped, the BSDF ray (shade_direct_hit) carries it all.
MCL_INLINE int direct_takes_light_samples(MCL_CONSTANT const FrameParams* f, Surface surf) {
  return f->directSampling != MCL_DIRECT_BRDF && (f->emitterCount > 0 || env_present(f) || f->lightCount > 0) &&
         !bsdf_is_delta(surf.bsdf);
}

MCL_INLINE void shade_direct_item(const shade_direct_args* a, uint i) {
  if (i >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  Hit h = a->hits[i];
  float3 dir = xyz(a->rays[i].dir);
  LightScene lights = make_light_scene(a->tris, a->normals, a->materials, a->emitters, a->envMap, a->envCdf, a->lightRecords,
                                       a->shading, make_texture_tables(a->textures, a->textureLevels, a->texels));
  Ray bounce;  // no BRDF ray unless set below; stored once on every way out
  bounce.origin = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  bounce.dir = make_float4(0.0f, 0.0f, 1.0f, -1.0f);
  if (!shade_begin(f, h, i, a->radiance, a->shadowContrib)) {
    a->bounce[i] = bounce;
    if (env_present(f)) a->radiance[i] = with_w(light_eval(f, lights, light_hit(h, dir)), 0.0f);
    return;
  }
  float3 le = light_eval(f, lights, light_hit(h, dir));  // Le of the hit triangle seen directly
  float3 wo = -dir;
  uint pixel = item_pixel(f, a->active, a->waveStart, i), sample = item_sample(f, a->waveStart, i);
  Surface surf = surface_at(MCL_STAGE_SURFACE_SCENE(a), f, h, hit_instance(f, a->hitInstances, i), dir,
                            sample_ref(pixel, sample, 0u));
  a->radiance[i] = with_w(le, 0.0f);
  float3 origin = offset_ray_origin(surf.frame.p, surf.frame.ng, f->offsetScale);
  int useBrdf = f->directSampling != MCL_DIRECT_LIGHT;
  for (uint k = 0; direct_takes_light_samples(f, surf) && k < f->lightSamples; ++k)
    direct_light_sample(a, lights, surf, wo, origin, useBrdf, i, k, sample_uniform4(f, pixel, sample, MCL_DIM_LIGHT + k));
  if (useBrdf) bounce = direct_bsdf_ray(f, surf, wo, origin, sample_uniform4(f, pixel, sample, MCL_DIM_BRDF));
  a->bounce[i] = bounce;
}
