// shade_direct_hit: reads each item's BSDF ray (bounce) and its closest hit (bounceHits), the
// camera hit, materials, the attribute buffer, textures and the environment; when the BSDF ray
// reached an emitter's front face, or escaped to the environment, writes (f cos / p) * Le * w_brdf
// (f cos / p: the kind's direction weight, lane_bsdf.h; w_brdf the MIS weight under mis; 1 at a
// delta surface, docs/estimators.md) to the item's BSDF shadow slot, K.
// The body takes W consecutive items, one per lane (W = MCL_LANES: 1 on the host backend and GPUs;
// lanes past the wave masked), in lane types: the light the BSDF ray found (Le with emission
// textures, lane_hit_emission; the environment; their light-sampling pdfs) and, where some lane
// found light, the camera hit's surface as shade_direct built it (lane_frame, lane_bsdf).
#pragma once
#include "stage_lanes.h"
#include "lane_bsdf.h"
#include "lane_lights.h"

MCL_INLINE void stage_shade_direct_hit(const shade_direct_hit_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, a->waveCount);
  const vmask own = v_lane_index() < lanes;
  // The lanes whose BSDF ray can have met light: traced, and reaching a material with some
  // positive Ke (material_emission is Ke there, or Ke times a texel) or escaping to an
  // environment. The others write nothing (their Le is 0).
  vfloat dx, dy, dz, dw, bt, btri, bu, bv;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->bounce + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  v_load4_n((MCL_GLOBAL const float*)(a->bounceHits + first), lanes, &bt, &btri, &bu, &bv);
  vuint tri = v_as_uint(btri);
  vmask miss = tri == MCL_NO_HIT;
  const vmask traced = own & (dw > 0.0f);
  LaneHits lit = lane_hits(f, a->tris, a->normals, a->materials, a->hitInstances, first, lanes, traced & v_not(miss), tri);
  vmask reach = traced & v_not(miss) & ((lit.ke.x > 0.0f) | (lit.ke.y > 0.0f) | (lit.ke.z > 0.0f));
  const int env = env_present(f);
  if (env) reach = reach | (traced & miss);
  if (!v_any(reach)) return;
  // Nothing here samples a light: no emitter table, no environment CDF.
  LightScene lights = make_light_scene(a->tris, a->normals, a->materials, 0, a->envMap, 0, 0, a->shading,
                                       make_texture_tables(a->textures, a->textureLevels, a->texels));
  const vfloat3 wi = v3_make(dx, dy, dz);
  const vfloat3 zero3 = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
  // Le (light_eval): the emitter's front face (emitted_toward), or the environment on a miss.
  vfloat3 ke = lit.ke;
  vfloat keLum = v_luminance(lit.ke);  // emitter_luminance
  const vmask glows = reach & v_not(miss);
  if (f->emissionTextured) ke = lane_hit_emission(lights, &lit, glows, bu, bv, &keLum);
  vmask emits = (v3_dot(lit.n, wi) < 0.0f) | (lit.twoSided != 0.0f);
  vfloat3 le = v3_select(glows & emits, ke, zero3);
  if (env && v_any(reach & miss)) le = v3_select(reach & miss, v_environment_light_eval_of(f, lights, wi), le);
  reach = reach & ((le.x > 0.0f) | (le.y > 0.0f) | (le.z > 0.0f));
  if (!v_any(reach)) return;
  // light_pdf: the area light's (with its share; 0 without emitters) or the environment's.
  vfloat pdfLight = v_f(0.0f);
  if (f->directSampling == MCL_DIRECT_MIS) {
    if (f->emitterCount > 0u && v_any(reach & v_not(miss)))
      pdfLight = area_light_probability(f) *
                 v_area_pdf_of(f, lit.area, keLum, bt * bt, v_emitter_cosine_of(lit.n, lit.twoSided, wi));
    if (env) pdfLight = vsel(miss, v_environment_light_pdf_of(f, lights, wi), pdfLight);
  }
  // The camera hit's surface (shade_direct's), its pdf and direction weight for wi.
  vfloat ht, htri, hu, hv;
  v_load4_n((MCL_GLOBAL const float*)(a->hits + first), lanes, &ht, &htri, &hu, &hv);
  LaneHits lh = lane_hits(f, a->tris, a->normals, a->materials, a->hitInstances, first, lanes, reach, v_as_uint(htri));
  vfloat cx, cy, cz, cw;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, lanes, &cx, &cy, &cz, &cw);
  const vfloat3 dir = v3_make(cx, cy, cz);
  vuint pixel, sample;
  v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
  LaneFrame sf = lane_frame(MCL_STAGE_SURFACE_SCENE(a), f, lane_bsdf_kinds(&lh) & v_not(lh.flat), pixel, sample, 0u,
                            &lh, hu, hv, ht, dir);
  const LaneBsdf lb = lane_bsdf(&lh, sf);
  const vfloat3 wo = v3_neg(dir);
  vfloat pdfBsdf;
  (void)lane_bsdf_eval_pdf(&lb, sf, wo, wi, &pdfBsdf);
  // A delta surface's BSDF ray is its only strategy (shade_direct skips light sampling there):
  // weight 1, no MIS.
  vfloat weight = vsel((pdfLight > 0.0f) & v_not(lane_bsdf_delta(&lb)),
                       v_power_heuristic_of(1.0f * pdfBsdf, (float)f->lightSamples * pdfLight), v_f(1.0f));
  vmask counts;
  vfloat3 fw = lane_bsdf_direction_weight(&lb, sf, wo, wi, pdfBsdf, &counts);
  vfloat3 c = v3_scale(v3_mul(fw, le), weight);
  uint set[MCL_LANES] MCL_LANE_ALIGN;
  float x[MCL_LANES] MCL_LANE_ALIGN, y[MCL_LANES] MCL_LANE_ALIGN, z[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(v_mask01(reach & counts), set);
  v3_store_lanes(c, x, y, z);
  for (uint j = 0; j < lanes; ++j)
    if (set[j]) a->shadowContrib[(first + j) * f->shadowSlots + f->lightSamples] = make_float4(x[j], y[j], z[j], 0.0f);
}
