// record_aov: reads camera rays, their hits, triangles (and their precomputed normals) and materials; writes each item's
// first-hit AOVs from surface_at (shared/surface.h): aov[2i] = (the BSDF's albedo, e.g. Kd x
// texture (camera ray cone footprint), depth along the camera ray), aov[2i + 1] = (shading normal
// on the camera's side, 0); zero where the camera ray hits nothing.
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_record_aov(const record_aov_args* a, uint i) {
  if (i >= a->waveCount) return;
  Hit h = a->hits[i];
  if (h.tri == MCL_NO_HIT) {
    a->aov[2 * i] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    a->aov[2 * i + 1] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    return;
  }
  Surface s = surface_at(MCL_STAGE_SURFACE_SCENE(a), a->frame, h, xyz(a->rays[i].dir));
  a->aov[2 * i] = with_w(bsdf_albedo(s.bsdf), h.t);
  a->aov[2 * i + 1] = with_w(s.frame.ns, 0.0f);
}
