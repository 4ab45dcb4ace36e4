// shade_ao: reads camera rays and their hits; writes radiance (background on a miss, else 0),
// clears the item's shadow slots, and pushes one AO occlusion query per hit onto the shadow queue
// (atomic counter) whose unoccluded value is the AO estimate V cos(theta) / (pi p(w)): 1 for
// cosine sampling, 2 cos(theta) for uniform sampling. The hemisphere is around the shading normal,
// a direction below the geometric surface folded above it (shared/shading.h).
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_shade_ao(const shade_ao_args* a, uint i) {
  if (i >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  Hit h = a->hits[i];
  if (!shade_begin(f, h, i, a->radiance, a->shadowContrib)) return;
  a->radiance[i] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float3 dir = xyz(a->rays[i].dir);
  SurfaceFrame sf = surface_frame_in(a->tris, a->normals, a->shading, a->instances, h,
                                    hit_instance(f, a->hitInstances, i), dir);
  float4 u = sample_uniform4(f, item_pixel(f, a->active, a->waveStart, i),
                          item_sample(f, a->waveStart, i), MCL_DIM_AO);
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
  float3 origin = offset_ray_origin(sf.p, sf.ng, f->offsetScale);
  push_shadow_query(a->queue, a->queueCount, origin, frame_sample_direction(sf, dirLocal), f->aoDistance,
                    make_float3(weight, weight, weight), i * f->shadowSlots);
}
