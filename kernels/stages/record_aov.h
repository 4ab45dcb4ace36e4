// record_aov: reads camera rays, their hits, triangles (and their precomputed normals) and materials; writes each item's
// first-hit AOVs: aov[2i] = (albedo Kd x texture (camera ray cone footprint), depth along the
// camera ray), aov[2i + 1] = (shading normal on the camera's side, 0: surface_frame); zero where
// the camera ray hits nothing.
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
  MCL_GLOBAL const Triangle* tri = &a->tris[h.tri];
  float3 albedo = hit_albedo(make_texture_tables(a->textures, a->textureLevels, a->texels), a->frame,
                             a->materials[triangle_material(tri)], tri, a->normals[h.tri], &a->shading[h.tri], h,
                             xyz(a->rays[i].dir));
  a->aov[2 * i] = with_w(albedo, h.t);
  a->aov[2 * i + 1] = with_w(surface_frame(a->tris, a->normals, a->shading, h, xyz(a->rays[i].dir)).ns, 0.0f);
}
