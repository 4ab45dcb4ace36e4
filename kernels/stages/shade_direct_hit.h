// shade_direct_hit: reads each item's BSDF ray (bounce) and its closest hit (bounceHits), the
// camera hit, materials, the attribute buffer, textures and the environment; when the BSDF ray
// reached an emitter's front face, or escaped to the environment, writes (f cos / p) * Le * w_brdf
// (f cos / p: bsdf_direction_weight of the surface's BSDF, shared/bsdf.h; w_brdf the MIS weight
// under mis; 1 at a delta surface, docs/estimators.md) to the item's BSDF shadow slot, K.
// The body takes W consecutive items, finds in lanes the few whose BSDF ray can have met light,
// and weighs those lane by lane.
#pragma once
#include "stage_lanes.h"
#include "direct_light.h"

// Item i's BSDF-ray contribution.
MCL_INLINE void direct_hit_weigh(const shade_direct_hit_args* a, uint i) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  Hit bh = a->bounceHits[i];
  if (!(a->bounce[i].dir.w > 0.0f)) return;
  float3 wi = xyz(a->bounce[i].dir);
  // Nothing here samples a light: no emitter table, no environment CDF.
  LightScene lights = make_light_scene(a->tris, a->normals, a->materials, 0, a->envMap, 0, 0, a->shading,
                                       make_texture_tables(a->textures, a->textureLevels, a->texels));
  LightHit lh = light_hit(bh, wi);  // the environment on a miss (no Le without one)
  float3 le = light_eval(f, lights, lh);
  if (!(le.x > 0.0f || le.y > 0.0f || le.z > 0.0f)) return;
  float pdfLight = f->directSampling == MCL_DIRECT_MIS ? light_pdf(f, lights, lh) : 0.0f;
  Hit h = a->hits[i];
  float3 dir = xyz(a->rays[i].dir);
  float3 wo = -dir;
  SampleRef r = sample_ref(item_pixel(f, a->active, a->waveStart, i), item_sample(f, a->waveStart, i), 0u);
  Surface surf = surface_at(MCL_STAGE_SURFACE_SCENE(a), f, h, hit_instance(f, a->hitInstances, i), dir, r);  // shade_direct's surface
  float pdfBsdf = bsdf_pdf(surf.bsdf, surf.frame, wo, wi);
  // A delta surface's BSDF ray is its only strategy (shade_direct skips light sampling there):
  // weight 1, no MIS.
  float weight = pdfLight > 0.0f && !bsdf_is_delta(surf.bsdf)
                     ? power_heuristic(1.0f, pdfBsdf, (float)f->lightSamples, pdfLight)
                     : 1.0f;
  BsdfWeight fw = bsdf_direction_weight(surf.bsdf, surf.frame, wo, wi, pdfBsdf);
  if (!fw.counts) return;
  a->shadowContrib[i * f->shadowSlots + f->lightSamples] = with_w(fw.weight * le * weight, 0.0f);
}

MCL_INLINE void stage_shade_direct_hit(const shade_direct_hit_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, a->waveCount);
  // The lanes whose BSDF ray can have met light, found in lanes: traced, and reaching a material
  // with some positive Ke (material_emission is Ke there, or Ke times a texel) or escaping to an
  // environment. Only those are weighed, one by one; the others write nothing, as the weighing
  // would not (its Le is 0).
  vfloat dx, dy, dz, dw, ht, htri, hu, hv;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->bounce + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  v_load4_n((MCL_GLOBAL const float*)(a->bounceHits + first), lanes, &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask miss = tri == MCL_NO_HIT;
  vfloat v0x, v0y, v0z, v0w, kex, key, kez, kew;
  v_gather4((MCL_GLOBAL const float*)a->tris, vsel(miss, v_u(0u), tri), 12, &v0x, &v0y, &v0z, &v0w);
  v_gather4((MCL_GLOBAL const float*)a->materials + 4, v_as_uint(v0w), MCL_MATERIAL_FLOATS, &kex, &key, &kez, &kew);
  vmask reach = v_not(miss) & ((kex > 0.0f) | (key > 0.0f) | (kez > 0.0f));
  if (env_present(f)) reach = reach | miss;
  uint set[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(v_mask01((v_lane_index() < lanes) & (dw > 0.0f) & reach), set);
  for (uint j = 0; j < lanes; ++j)
    if (set[j]) direct_hit_weigh(a, first + j);
}
