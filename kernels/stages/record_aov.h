// record_aov: reads camera rays, their hits, triangles (and their precomputed normals), materials
// and each item's radiance as the shade stage left it; writes each item's first-hit AOVs from
// surface_at (shared/surface.h): aov[3i] = (the BSDF's albedo, e.g. Kd x texture (camera ray cone
// footprint), depth along the camera ray), aov[3i + 1] = (shading normal on the camera's side, 0),
// both zero where the camera ray hits nothing; aov[3i + 2] = (emission seen directly, 0).
// The emission is radiance[i] copied: it runs after the shade stage and before anything adds a
// light sample to radiance (accumulate adds the shadow slots; path_gather runs after it), so it is
// exactly the camera ray's own term of the sample (Le of the hit seen directly, the environment or
// background on a miss, 0 on an AO hit), bit for bit what the estimate holds.
#pragma once
#include "stage_common.h"

MCL_INLINE void record_aov_item(const record_aov_args* a, uint i) {
  if (i >= a->waveCount) return;
  Hit h = a->hits[i];
  a->aov[MCL_AOV_VECTORS * i + 2] = with_w(xyz(a->radiance[i]), 0.0f);
  if (h.tri == MCL_NO_HIT) {
    a->aov[MCL_AOV_VECTORS * i] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    a->aov[MCL_AOV_VECTORS * i + 1] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    return;
  }
  // The camera hit's surface as the shade stage built it (the same kind of a partly transmissive
  // material): wave item i is path i at bounce 0.
  SampleRef r = sample_ref(item_pixel(a->frame, a->active, a->waveStart, i), item_sample(a->frame, a->waveStart, i), 0u);
  Surface s = surface_at(MCL_STAGE_SURFACE_SCENE(a), a->frame, h, hit_instance(a->frame, a->hitInstances, i),
                         xyz(a->rays[i].dir), r);
  a->aov[MCL_AOV_VECTORS * i] = with_w(bsdf_albedo(s.bsdf), h.t);
  a->aov[MCL_AOV_VECTORS * i + 1] = with_w(s.frame.ns, 0.0f);
}
