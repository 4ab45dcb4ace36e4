// record_aov_lanes.h: the packet form of record_aov (record_aov.h), the same AOVs per item: W
// consecutive camera hits, one per lane. Where the surface is flat (no shading normals), of the
// diffuse kind, without vertex colours, an albedo texture or a normal or bump map, the albedo is
// the material's Kd and the normal the geometric one facing the camera; the other lanes run the
// scalar body after the packet, and so does every item of a partial last packet or an instanced
// scene.
#pragma once
#include "record_aov.h"
#include "stage_lanes.h"

MCL_INLINE void stage_record_aov(const record_aov_args* a, uint first) {
  if (first >= a->waveCount) return;
  if (v_packet_partial(first, a->waveCount) || a->frame->instanceCount > 0u) {
    for (uint k = 0; k < MCL_LANES && first + k < a->waveCount; ++k) record_aov_item(a, first + k);
    return;
  }
  vfloat ht, htri, hu, hv;
  v_load4((MCL_GLOBAL const float*)(a->hits + first), &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = tri != MCL_NO_HIT;
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
  vmask packet = hit & ((v_as_uint(e2w) & (MCL_ATTR_NORMALS | MCL_ATTR_COLOR)) == 0u) &
                 (v_as_uint(kdw) == MCL_NO_TEXTURE) & (v_as_uint(kaw) == (uint)MCL_MATERIAL_diffuse) &
                 (v_as_uint(kmz) == 0u) & (v_as_uint(kmw) == 0u);
  vfloat dx, dy, dz, dw;
  v_load4_stride((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, &dx, &dy, &dz, &dw);
  vfloat3 ns = v_orient_facing(v3_make(nx, ny, nz), v3_make(dx, dy, dz));  // surface_frame, flat
  vfloat rx, ry, rz, rw;
  v_load4((MCL_GLOBAL const float*)(a->radiance + first), &rx, &ry, &rz, &rw);
  MCL_GLOBAL float* out = (MCL_GLOBAL float*)(a->aov + MCL_AOV_VECTORS * first);
  const vfloat zero = v_f(0.0f);
  v_store4_stride(out, 4 * MCL_AOV_VECTORS, vsel(hit, kdx, zero), vsel(hit, kdy, zero), vsel(hit, kdz, zero),
                  vsel(hit, ht, zero));
  v_store4_stride(out + 4, 4 * MCL_AOV_VECTORS, vsel(hit, ns.x, zero), vsel(hit, ns.y, zero), vsel(hit, ns.z, zero),
                  zero);
  v_store4_stride(out + 8, 4 * MCL_AOV_VECTORS, rx, ry, rz, zero);
  vmask scalar = hit & v_not(packet);
  if (v_any(scalar)) {
    uint s[MCL_LANES] MCL_LANE_ALIGN;
    v_store_lanes(v_mask01(scalar), s);
    for (uint k = 0; k < MCL_LANES; ++k)
      if (s[k]) record_aov_item(a, first + k);
  }
}
