// stages_direct.h: the direct-lighting shade stages for one work item, shared by the kernels and
// the host. Lambertian surfaces (f = Kd / pi), geometric normal facing the incoming ray; emitters
// emit Ke from their front face (the side of cross(e1, e2)). Slots per sample: [0, K) light
// samples, K the BRDF sample; each strategy leaves the slots it does not use at 0.
#pragma once
#include "lights.h"
#include "stages.h"

// Le leaving tri toward the viewer moving along dir (0 from the back face).
MCL_INLINE float3 emitted_toward(MCL_GLOBAL const Triangle* tri, MCL_GLOBAL const Material* materials,
                                 float3 dir) {
  float3 e = xyz(materials[triangle_material(tri)].emission);
  return dot(cross(xyz(tri->e1), xyz(tri->e2)), dir) < 0.0f ? e : make_float3(0.0f, 0.0f, 0.0f);
}

// shade_direct: for camera item i writes radiance[i] (background, or Le seen directly), pushes K
// light-sample occlusion queries (light / mis) and writes the BRDF ray bounce[i] (brdf / mis;
// otherwise an empty ray with tmax < 0).
MCL_INLINE void stage_shade_direct(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                                   ulong waveStart,
                                   MCL_GLOBAL const Triangle* tris,
                                   MCL_GLOBAL const Material* materials,
                                   MCL_GLOBAL const Emitter* emitters, MCL_GLOBAL const Ray* rays,
                                   MCL_GLOBAL const Hit* hits, uint i, MCL_GLOBAL float4* radiance,
                                   MCL_GLOBAL float4* shadowContrib, MCL_GLOBAL ShadowWork* queue,
                                   MCL_GLOBAL volatile uint* queueCount, MCL_GLOBAL Ray* bounce) {
  Hit h = hits[i];
  for (uint k = 0; k < f->shadowSlots; ++k)
    shadowContrib[i * f->shadowSlots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  bounce[i].origin = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  bounce[i].dir = make_float4(0.0f, 0.0f, 1.0f, -1.0f);
  if (h.tri == MCL_NO_HIT) {
    radiance[i] = f->background;
    return;
  }
  float3 dir = xyz(rays[i].dir);
  MCL_GLOBAL const Triangle* tri = &tris[h.tri];
  radiance[i] = with_w(emitted_toward(tri, materials, dir), 0.0f);
  float3 n = facing_normal(tri, dir);
  float3 albedo = xyz(materials[triangle_material(tri)].albedo);
  float3 origin = offset_ray_origin(hit_position(tri, h), n);
  uint pixel = item_pixel(f, active, waveStart, i), sample = item_sample(f, waveStart, i);
  float nLight = (float)f->lightSamples;
  bool useLight = f->directSampling != MCL_DIRECT_BRDF && f->emitterCount > 0;
  bool useBrdf = f->directSampling != MCL_DIRECT_LIGHT;

  for (uint k = 0; useLight && k < f->lightSamples; ++k) {
    float4 u = rng_uniform4(f->seed, pixel, sample, MCL_DIM_LIGHT + k);
    MCL_GLOBAL const Emitter* em = &emitters[pick_emitter(emitters, f->emitterCount, u.x)];
    MCL_GLOBAL const Triangle* lt = &tris[em->tri];
    float3 le = xyz(materials[triangle_material(lt)].emission);
    float3 p = sample_triangle(xyz(lt->v0), xyz(lt->e1), xyz(lt->e2), u.y, u.z);
    float3 toLight = p - origin;
    float dist2 = dot(toLight, toLight);
    float dist = sqrt(dist2);
    float3 wi = toLight / dist;
    float3 lightN = cross(xyz(lt->e1), xyz(lt->e2));
    float cosLight = -dot(normalize(lightN), wi);
    float cosSurf = dot(n, wi);
    if (!(cosLight > 0.0f && cosSurf > 0.0f && dist > 0.0f)) continue;
    float pick = emitter_pick_probability(em->area, le, f->emitterPower);
    float pdfLight = area_to_solid_angle(pick / em->area, dist2, cosLight);
    float weight = useBrdf ? power_heuristic(nLight, pdfLight, 1.0f, pdf_cosine_hemisphere(cosSurf)) : 1.0f;
    float3 c = albedo * MCL_INV_PI * le * (cosSurf * weight / (pdfLight * nLight));
    ShadowWork w;
    w.ray.origin = with_w(origin, 0.0f);
    w.ray.dir = with_w(wi, dist * (1.0f - 1e-4f));
    w.r = c.x;
    w.g = c.y;
    w.b = c.z;
    w.slot = i * f->shadowSlots + k;
    queue[MCL_ATOMIC_INC(queueCount)] = w;
  }
  if (useBrdf) {
    float4 u = rng_uniform4(f->seed, pixel, sample, MCL_DIM_BRDF);
    bounce[i].origin = with_w(origin, 0.0f);
    bounce[i].dir = with_w(to_world(sample_cosine_hemisphere(u.x, u.y), n), INFINITY);
  }
}

// shade_direct_hit: when the BRDF ray of item i reached an emitter's front face, writes
// Kd * Le * w_brdf (f cos / p = Kd for cosine sampling) to the item's BRDF slot.
MCL_INLINE void stage_shade_direct_hit(MCL_CONSTANT const FrameParams* f,
                                       MCL_GLOBAL const Triangle* tris,
                                       MCL_GLOBAL const Material* materials,
                                       MCL_GLOBAL const Ray* rays, MCL_GLOBAL const Hit* hits,
                                       MCL_GLOBAL const Ray* bounce,
                                       MCL_GLOBAL const Hit* bounceHits, uint i,
                                       MCL_GLOBAL float4* shadowContrib) {
  Hit bh = bounceHits[i];
  if (bh.tri == MCL_NO_HIT || !(bounce[i].dir.w > 0.0f)) return;
  float3 wi = xyz(bounce[i].dir);
  MCL_GLOBAL const Triangle* lt = &tris[bh.tri];
  float3 le = emitted_toward(lt, materials, wi);
  if (!(le.x > 0.0f || le.y > 0.0f || le.z > 0.0f)) return;
  MCL_GLOBAL const Triangle* tri = &tris[hits[i].tri];
  float3 n = facing_normal(tri, xyz(rays[i].dir));
  float3 albedo = xyz(materials[triangle_material(tri)].albedo);
  float weight = 1.0f;
  if (f->directSampling == MCL_DIRECT_MIS && f->emitterCount > 0) {
    float area = triangle_area(lt);
    float cosLight = -dot(normalize(cross(xyz(lt->e1), xyz(lt->e2))), wi);
    float pick = emitter_pick_probability(area, xyz(materials[triangle_material(lt)].emission), f->emitterPower);
    float pdfLight = area_to_solid_angle(pick / area, bh.t * bh.t, cosLight);
    weight = power_heuristic(1.0f, pdf_cosine_hemisphere(dot(n, wi)), (float)f->lightSamples, pdfLight);
  }
  shadowContrib[i * f->shadowSlots + f->lightSamples] = with_w(albedo * le * weight, 0.0f);
}
