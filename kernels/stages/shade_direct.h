// shade_direct: reads camera rays, hits, materials and the emitter table; for camera item i writes
// radiance[i] (background, or Le seen directly), pushes K light-sample occlusion queries onto the
// shadow queue (light / mis) and writes the BRDF ray bounce[i] (brdf / mis; otherwise an empty
// ray with tmax < 0). Lambertian surfaces (f = albedo / pi, albedo = Kd x texture,
// surface_texture.h) with the shading normal's cosine; light directions below the geometric
// surface are zero, BRDF directions folded above it (shared/shading.h).
// Shadow slots per sample: [0, K) light samples, K the BRDF sample (shade_direct_hit); each
// strategy leaves the slots it does not use at 0.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_shade_direct(const shade_direct_args* a, uint i) {
  if (i >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  Hit h = a->hits[i];
  a->bounce[i].origin = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  a->bounce[i].dir = make_float4(0.0f, 0.0f, 1.0f, -1.0f);  // no BRDF ray unless written below
  if (!shade_begin(f, h, i, a->radiance, a->shadowContrib)) return;
  MCL_GLOBAL const Triangle* tris = a->tris;
  MCL_GLOBAL const Material* materials = a->materials;
  float3 dir = xyz(a->rays[i].dir);
  MCL_GLOBAL const Triangle* tri = &tris[h.tri];
  a->radiance[i] = with_w(emitted_toward(tri, materials, dir), 0.0f);
  SurfaceFrame sf = surface_frame(tris, a->shading, h, dir);
  float3 albedo = hit_albedo(make_texture_tables(a->textures, a->textureLevels, a->texels),
                             materials[triangle_material(tri)], tri, &a->shading[h.tri], h, dir,
                             camera_spread_angle(f) * h.t);
  float3 origin = offset_ray_origin(sf.p, sf.ng, f->offsetScale);
  uint pixel = item_pixel(f, a->active, a->waveStart, i), sample = item_sample(f, a->waveStart, i);
  float nLight = (float)f->lightSamples;
  bool useLight = f->directSampling != MCL_DIRECT_BRDF && f->emitterCount > 0;
  bool useBrdf = f->directSampling != MCL_DIRECT_LIGHT;

  for (uint k = 0; useLight && k < f->lightSamples; ++k) {
    float4 u = rng_uniform4(f->seed, pixel, sample, MCL_DIM_LIGHT + k);
    MCL_GLOBAL const Emitter* em = &a->emitters[pick_emitter(a->emitters, f->emitterCount, u.x)];
    MCL_GLOBAL const Triangle* lt = &tris[em->tri];
    float3 le = xyz(materials[triangle_material(lt)].emission);
    float3 p = sample_triangle(xyz(lt->v0), xyz(lt->e1), xyz(lt->e2), u.y, u.z);
    float3 toLight = p - origin;
    float dist2 = dot(toLight, toLight);
    float dist = sqrt(dist2);
    float3 wi = toLight / dist;
    float cosLight = emitter_cosine(lt, materials, wi);
    float cosSurf = frame_cosine(sf, wi);  // 0 below the geometric surface
    if (!(cosLight > 0.0f && cosSurf > 0.0f && dist > 0.0f)) continue;
    float pick = emitter_pick_probability(em->area, le, f->emitterPower);
    float pdfLight = area_to_solid_angle(pick / em->area, dist2, cosLight);
    float weight = useBrdf ? power_heuristic(nLight, pdfLight, 1.0f, frame_pdf_cosine(sf, wi)) : 1.0f;
    float3 c = albedo * MCL_INV_PI * le * (cosSurf * weight / (pdfLight * nLight));
    ShadowWork w;
    w.ray.origin = with_w(origin, 0.0f);
    w.ray.dir = with_w(wi, dist * (1.0f - 1e-4f));
    w.r = c.x;
    w.g = c.y;
    w.b = c.z;
    w.slot = i * f->shadowSlots + k;
    a->queue[MCL_ATOMIC_INC(a->queueCount)] = w;
  }
  if (useBrdf) {
    float4 u = rng_uniform4(f->seed, pixel, sample, MCL_DIM_BRDF);
    a->bounce[i].origin = with_w(origin, 0.0f);
    a->bounce[i].dir = with_w(frame_sample_direction(sf, sample_cosine_hemisphere(u.x, u.y)), INFINITY);
  }
}
