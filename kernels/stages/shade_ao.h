// shade_ao: reads the camera rays and hits of wave items first .. first + W - 1, one per lane (W =
// MCL_LANES: 1 on the host backend and GPUs); writes their radiance (background on a miss, else 0),
// clears their shadow slots, and pushes one AO occlusion query per hit onto the shadow queue (one
// atomic per packet) whose unoccluded value is the AO estimate V cos(theta) / (pi p(w)): 1 for
// cosine sampling, 2 cos(theta) for uniform sampling. The hemisphere is around the shading normal,
// a direction below the geometric surface folded above it (shared/shading.h). Lanes past the wave
// are masked.
#pragma once
#include "stage_lanes.h"

MCL_INLINE void stage_shade_ao(const shade_ao_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, a->waveCount);
  vfloat ht, htri, hu, hv;
  v_load4_n((MCL_GLOBAL const float*)(a->hits + first), lanes, &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = (tri != MCL_NO_HIT) & (v_lane_index() < lanes);
  // Every lane with an item: shadow slots cleared; radiance the background on a miss, else 0.
  const uint slots = f->shadowSlots;
  for (uint k = 0; k < lanes * slots; ++k)
    a->shadowContrib[first * slots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 bg = f->background;
  v_store4_n((MCL_GLOBAL float*)(a->radiance + first), lanes, vsel(hit, v_f(0.0f), v_f(bg.x)),
             vsel(hit, v_f(0.0f), v_f(bg.y)), vsel(hit, v_f(0.0f), v_f(bg.z)), vsel(hit, v_f(0.0f), v_f(bg.w)));
  if (!v_any(hit)) return;
  vfloat dx, dy, dz, dw;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  LaneFrame sf = lane_surface_frame(a->tris, a->normals, a->shading, a->instances, f, a->hitInstances, first, lanes,
                                    hit, tri, hu, hv, v3_make(dx, dy, dz));
  vuint pixel, sample;
  v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
  vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_AO);
  vfloat3 dirLocal;
  vfloat weight;
  if (f->aoSampling == MCL_AO_COSINE) {
    dirLocal = v_sample_cosine_hemisphere(u.x, u.y);
    weight = v_f(1.0f);  // cos / (pi * cos / pi)
  } else {
    dirLocal = v_sample_uniform_hemisphere(u.x, u.y);
    weight = 2.0f * dirLocal.z;  // cos / (pi / (2 pi))
  }
  vmask push = hit & (weight > 0.0f);
  vfloat3 origin = v_offset_ray_origin(sf.p, sf.ng, f->offsetScale);
  v_push_shadow_queries(a->queue, a->queueCount, push, origin, lane_frame_sample_direction(sf, dirLocal),
                        v_f(f->aoDistance), v3_make(weight, weight, weight), (first + v_lane_index()) * slots);
}
