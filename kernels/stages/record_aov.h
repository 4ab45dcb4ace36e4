// record_aov: reads the camera rays and hits of wave items first .. first + W - 1, one per lane (W =
// MCL_LANES: 1 on the host backend and GPUs), their triangles (and precomputed normals), materials,
// attributes, textures and instances, and radiance as the shade stage left it; writes each item's
// first-hit AOVs: aov[3i] = (the BSDF's albedo, e.g. Kd x texture (camera ray cone footprint),
// depth along the camera ray), aov[3i + 1] = (shading normal on the camera's side, 0), both zero
// where the camera ray hits nothing; aov[3i + 2] = (emission seen directly, 0).
// The emission is radiance[i] copied: it runs after the shade stage and before anything adds a
// light sample to radiance (accumulate adds the shadow slots; path_gather runs after it), so it is
// exactly the camera ray's own term of the sample (Le of the hit seen directly, the environment or
// background on a miss, 0 on an AO hit), bit for bit what the estimate holds.
// The surface is the one the shade stage built, in lanes: lane_frame (stage_lanes.h) and every
// material kind's albedo (lane_bsdf.h); wave item i is path i at bounce 0. Lanes past the wave are
// masked.
#pragma once
#include "stage_lanes.h"
#include "lane_bsdf.h"

MCL_INLINE void stage_record_aov(const record_aov_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, a->waveCount);
  vfloat ht, htri, hu, hv;
  v_load4_n((MCL_GLOBAL const float*)(a->hits + first), lanes, &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = (tri != MCL_NO_HIT) & (v_lane_index() < lanes);
  vfloat dx, dy, dz, dw;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  const vfloat zero = v_f(0.0f);
  vfloat3 albedo = v3_make(zero, zero, zero), ns = albedo;
  if (v_any(hit)) {
    LaneHits lh = lane_hits(f, a->tris, a->normals, a->materials, a->hitInstances, first, lanes, hit, tri);
    vuint pixel, sample;
    v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
    LaneFrame sf = lane_frame(MCL_STAGE_SURFACE_SCENE(a), f, lane_bsdf_kinds(&lh) & v_not(lh.flat), pixel, sample, 0u,
                              &lh, hu, hv, ht, v3_make(dx, dy, dz));
    const LaneBsdf lb = lane_bsdf(&lh, sf);
    albedo = lane_bsdf_albedo(&lb);
    ns = sf.ns;
  }
  vfloat rx, ry, rz, rw;
  v_load4_n((MCL_GLOBAL const float*)(a->radiance + first), lanes, &rx, &ry, &rz, &rw);
  MCL_GLOBAL float* out = (MCL_GLOBAL float*)(a->aov + MCL_AOV_VECTORS * first);
  const uint stride = 4 * MCL_AOV_VECTORS;
  v_store4_stride_n(out, stride, lanes, vsel(hit, albedo.x, zero), vsel(hit, albedo.y, zero),
                    vsel(hit, albedo.z, zero), vsel(hit, ht, zero));
  v_store4_stride_n(out + 4, stride, lanes, vsel(hit, ns.x, zero), vsel(hit, ns.y, zero), vsel(hit, ns.z, zero), zero);
  v_store4_stride_n(out + 8, stride, lanes, rx, ry, rz, zero);
}
