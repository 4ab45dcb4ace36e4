// shade_ao_lanes.h: the packet form of shade_ao (shade_ao.h), the same bits per item: W
// consecutive camera hits, one per lane; the AO queries of the packet take one atomic. Hits on
// triangles with shading normals, and a partial last packet, run the scalar body per item.
#pragma once
#include "shade_ao.h"
#include "stage_lanes.h"

MCL_INLINE void stage_shade_ao_lanes(const shade_ao_args* a, uint first) {
  if (first >= a->waveCount) return;
  // Instanced hits are shaded in their object space: the scalar body per lane.
  if (v_packet_partial(first, a->waveCount) || a->frame->instanceCount > 0u) {
    for (uint k = 0; k < MCL_LANES && first + k < a->waveCount; ++k) stage_shade_ao(a, first + k);
    return;
  }
  MCL_CONSTANT const FrameParams* f = a->frame;
  vfloat ht, htri, hu, hv;
  v_load4((MCL_GLOBAL const float*)(a->hits + first), &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = tri != MCL_NO_HIT;
  // shade_begin for every lane: shadow slots cleared; radiance the background on a miss, else 0.
  const uint slots = f->shadowSlots;
  for (uint k = 0; k < MCL_LANES * slots; ++k)
    a->shadowContrib[first * slots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 bg = f->background;
  v_store4((MCL_GLOBAL float*)(a->radiance + first), vsel(hit, v_f(0.0f), v_f(bg.x)), vsel(hit, v_f(0.0f), v_f(bg.y)),
           vsel(hit, v_f(0.0f), v_f(bg.z)), vsel(hit, v_f(0.0f), v_f(bg.w)));
  if (!v_any(hit)) return;
  // surface_frame of the hit lanes (misses read triangle 0 and are masked off).
  vuint t = vsel(hit, tri, v_u(0u));
  MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)a->tris;
  vfloat v0x, v0y, v0z, v0w, e1x, e1y, e1z, e1w, e2x, e2y, e2z, e2w, nx, ny, nz, nw;
  v_gather4(tf, t, 12, &v0x, &v0y, &v0z, &v0w);
  v_gather4(tf + 4, t, 12, &e1x, &e1y, &e1z, &e1w);
  v_gather4(tf + 8, t, 12, &e2x, &e2y, &e2z, &e2w);
  v_gather4((MCL_GLOBAL const float*)a->normals, t, 4, &nx, &ny, &nz, &nw);
  vmask smooth = hit & ((v_as_uint(e2w) & MCL_ATTR_NORMALS) != 0u);  // the scalar body's lanes
  vmask flat = hit & v_not(smooth);
  if (v_any(flat)) {
    vfloat dx, dy, dz, dw;
    v_load4_stride((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, &dx, &dy, &dz, &dw);
    vfloat3 dir = v3_make(dx, dy, dz);
    vfloat3 p = v3_add(v3_add(v3_make(v0x, v0y, v0z), v3_scale(v3_make(e1x, e1y, e1z), hu)),
                       v3_scale(v3_make(e2x, e2y, e2z), hv));
    vfloat3 ng = v_orient_facing(v3_make(nx, ny, nz), dir);
    vuint pixel, sample;
    v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
    vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_AO);
    vfloat3 dirLocal;
    vfloat weight;
    if (f->aoSampling == MCL_AO_COSINE) {
      dirLocal = v_sample_cosine_hemisphere(u.x, u.y);
      weight = v_f(1.0f);
    } else {
      dirLocal = v_sample_uniform_hemisphere(u.x, u.y);
      weight = 2.0f * dirLocal.z;
    }
    vmask push = flat & (weight > 0.0f);
    vfloat3 origin = v_offset_ray_origin(p, ng, f->offsetScale);
    vfloat3 w = v_to_world(dirLocal, ng);  // frame_sample_direction without a shading normal
    v_push_shadow_queries(a->queue, a->queueCount, push, origin, w, v_f(f->aoDistance), v3_make(weight, weight, weight),
                          (first + v_lane_index()) * slots);
  }
  if (v_any(smooth)) {
    uint s[MCL_LANES] MCL_LANE_ALIGN;
    v_store_lanes(v_mask01(smooth), s);
    for (uint k = 0; k < MCL_LANES; ++k)
      if (s[k]) stage_shade_ao(a, first + k);
  }
}
