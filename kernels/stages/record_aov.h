// record_aov: reads the camera rays and hits of wave items first .. first + W - 1, one per lane (W =
// MCL_LANES: 1 on the host backend and GPUs), their triangles (and precomputed normals), materials
// and radiance as the shade stage left it; writes each item's first-hit AOVs from surface_at
// (shared/surface.h): aov[3i] = (the BSDF's albedo, e.g. Kd x texture (camera ray cone footprint),
// depth along the camera ray), aov[3i + 1] = (shading normal on the camera's side, 0), both zero
// where the camera ray hits nothing; aov[3i + 2] = (emission seen directly, 0).
// The emission is radiance[i] copied: it runs after the shade stage and before anything adds a
// light sample to radiance (accumulate adds the shadow slots; path_gather runs after it), so it is
// exactly the camera ray's own term of the sample (Le of the hit seen directly, the environment or
// background on a miss, 0 on an AO hit), bit for bit what the estimate holds.
// Where the surface is flat (no shading normals), of the diffuse kind, without vertex colours, an
// albedo texture or a normal or bump map, in world space, the albedo is the material's Kd and the
// normal the geometric one facing the camera, in lanes; the other hits' lanes take surface_at and
// bsdf_albedo one by one. Lanes past the wave are masked.
#pragma once
#include "stage_lanes.h"

MCL_INLINE void stage_record_aov(const record_aov_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, a->waveCount);
  vfloat ht, htri, hu, hv;
  v_load4_n((MCL_GLOBAL const float*)(a->hits + first), lanes, &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = (tri != MCL_NO_HIT) & (v_lane_index() < lanes);
  vuint t = vsel(hit, tri, v_u(0u));  // misses read entry 0 and are masked off
  MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)a->tris;
  MCL_GLOBAL const float* mf = (MCL_GLOBAL const float*)a->materials;
  vfloat v0x, v0y, v0z, v0w, e2x, e2y, e2z, e2w, nx, ny, nz, nw;
  v_gather4(tf, t, 12, &v0x, &v0y, &v0z, &v0w);
  v_gather4(tf + 8, t, 12, &e2x, &e2y, &e2z, &e2w);
  v_gather4((MCL_GLOBAL const float*)a->normals, t, 4, &nx, &ny, &nz, &nw);
  vuint mat = v_as_uint(v0w);  // triangle_material
  vfloat kdx, kdy, kdz, kdw, kax, kay, kaz, kaw, kmx, kmy, kmz, kmw;
  v_gather4(mf, mat, MCL_MATERIAL_FLOATS, &kdx, &kdy, &kdz, &kdw);       // albedo: Kd, texture index
  v_gather4(mf + 12, mat, MCL_MATERIAL_FLOATS, &kax, &kay, &kaz, &kaw);  // w: the material kind (uint bits)
  v_gather4(mf + 24, mat, MCL_MATERIAL_FLOATS, &kmx, &kmy, &kmz, &kmw);  // maps: z the normal map, w the bump map (+1)
  vmask lean = hit & ((v_as_uint(e2w) & (MCL_ATTR_NORMALS | MCL_ATTR_COLOR)) == 0u) &
               (v_as_uint(kdw) == MCL_NO_TEXTURE) & (v_as_uint(kaw) == (uint)MCL_MATERIAL_diffuse) &
               (v_as_uint(kmz) == 0u) & (v_as_uint(kmw) == 0u);
  if (f->instanceCount > 0u) lean = hit & v_not(hit);  // instanced hits are shaded in object space
  vfloat dx, dy, dz, dw;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  vfloat3 ns = v_orient_facing(v3_make(nx, ny, nz), v3_make(dx, dy, dz));  // surface_frame, flat
  vfloat rx, ry, rz, rw;
  v_load4_n((MCL_GLOBAL const float*)(a->radiance + first), lanes, &rx, &ry, &rz, &rw);
  MCL_GLOBAL float* out = (MCL_GLOBAL float*)(a->aov + MCL_AOV_VECTORS * first);
  const vfloat zero = v_f(0.0f);
  const uint stride = 4 * MCL_AOV_VECTORS;
  v_store4_stride_n(out, stride, lanes, vsel(hit, kdx, zero), vsel(hit, kdy, zero), vsel(hit, kdz, zero),
                    vsel(hit, ht, zero));
  v_store4_stride_n(out + 4, stride, lanes, vsel(hit, ns.x, zero), vsel(hit, ns.y, zero), vsel(hit, ns.z, zero), zero);
  v_store4_stride_n(out + 8, stride, lanes, rx, ry, rz, zero);
  vmask rich = hit & v_not(lean);
  if (!v_any(rich)) return;
  uint set[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(v_mask01(rich), set);
  for (uint k = 0; k < MCL_LANES; ++k) {
    if (!set[k]) continue;
    // The camera hit's surface as the shade stage built it (the same kind of a partly transmissive
    // material): wave item i is path i at bounce 0.
    const uint i = first + k;
    Hit h = a->hits[i];
    SampleRef r = sample_ref(item_pixel(f, a->active, a->waveStart, i), item_sample(f, a->waveStart, i), 0u);
    Surface s = surface_at(MCL_STAGE_SURFACE_SCENE(a), f, h, hit_instance(f, a->hitInstances, i), xyz(a->rays[i].dir), r);
    a->aov[MCL_AOV_VECTORS * i] = with_w(bsdf_albedo(s.bsdf), h.t);
    a->aov[MCL_AOV_VECTORS * i + 1] = with_w(s.frame.ns, 0.0f);
  }
}
