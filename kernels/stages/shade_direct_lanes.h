// shade_direct_lanes.h: the packet form of shade_direct (shade_direct.h) for the common case, the
// same bits per item: W consecutive camera hits, one per lane, on flat (no shading normals),
// untextured, Lambertian surfaces of the diffuse kind (no glossy lobe) lit by emitter triangles: Le seen directly, the
// light samples (an emitter by power, a uniform point on it; one atomic per packet per light
// sample) and the BSDF ray (cosine lobe). Lanes that hit anything else (shading normals, an albedo
// texture, a normal map, a glossy lobe) run the scalar body after the packet; so does every item of a packet
// when an environment or a light record (point, spot, directional) lights the scene or an emission
// is textured, and of a partial last packet.
#pragma once
#include "shade_direct.h"
#include "light_area_lanes.h"
#include "stage_lanes.h"

MCL_INLINE void stage_shade_direct_lanes(const shade_direct_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  if (v_packet_partial(first, a->waveCount) || env_present(f) || f->lightCount > 0u || f->emissionTextured ||
      f->instanceCount > 0u) {  // (instanced hits are shaded in their object space by the scalar body)
    for (uint k = 0; k < MCL_LANES && first + k < a->waveCount; ++k) stage_shade_direct(a, first + k);
    return;
  }
  vfloat ht, htri, hu, hv;
  v_load4((MCL_GLOBAL const float*)(a->hits + first), &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = tri != MCL_NO_HIT;
  const uint slots = f->shadowSlots;
  for (uint k = 0; k < MCL_LANES * slots; ++k)  // shade_begin
    a->shadowContrib[first * slots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 bg = f->background;
  MCL_GLOBAL float* rad = (MCL_GLOBAL float*)(a->radiance + first);
  MCL_GLOBAL float* bounce = (MCL_GLOBAL float*)(a->bounce + first);
  if (!v_any(hit)) {
    v_store4(rad, v_f(bg.x), v_f(bg.y), v_f(bg.z), v_f(bg.w));
    v_store4_stride(bounce, 8, v_f(0.0f), v_f(0.0f), v_f(0.0f), v_f(0.0f));
    v_store4_stride(bounce + 4, 8, v_f(0.0f), v_f(0.0f), v_f(1.0f), v_f(-1.0f));
    return;
  }
  // The hit triangles, their normals and materials (misses read entry 0 and are masked off).
  vuint t = vsel(hit, tri, v_u(0u));
  MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)a->tris;
  MCL_GLOBAL const float* mf = (MCL_GLOBAL const float*)a->materials;
  vfloat v0x, v0y, v0z, v0w, e1x, e1y, e1z, e1w, e2x, e2y, e2z, e2w, nx, ny, nz, nw;
  v_gather4(tf, t, 12, &v0x, &v0y, &v0z, &v0w);
  v_gather4(tf + 4, t, 12, &e1x, &e1y, &e1z, &e1w);
  v_gather4(tf + 8, t, 12, &e2x, &e2y, &e2z, &e2w);
  v_gather4((MCL_GLOBAL const float*)a->normals, t, 4, &nx, &ny, &nz, &nw);
  vuint mat = v_as_uint(v0w);  // triangle_material
  vfloat kdx, kdy, kdz, kdw, kex, key, kez, kew, ksx, ksy, ksz, ksw;
  v_gather4(mf, mat, MCL_MATERIAL_FLOATS, &kdx, &kdy, &kdz, &kdw);      // albedo: Kd, texture index
  v_gather4(mf + 4, mat, MCL_MATERIAL_FLOATS, &kex, &key, &kez, &kew);  // emission: Ke, two-sided
  v_gather4(mf + 8, mat, MCL_MATERIAL_FLOATS, &ksx, &ksy, &ksz, &ksw);  // specular: Ks, alpha
  vfloat kax, kay, kaz, kaw;
  v_gather4(mf + 12, mat, MCL_MATERIAL_FLOATS, &kax, &kay, &kaz, &kaw);  // alpha test; w: the material kind (uint bits)
  vfloat kmx, kmy, kmz, kmw;
  v_gather4(mf + 24, mat, MCL_MATERIAL_FLOATS, &kmx, &kmy, &kmz, &kmw);  // maps: z the normal map, w the bump map (+1)
  // bsdf_make's specProb, as the scalar body computes it: the packet takes the lanes where it is 0.
  vfloat ls = v_luminance(v3_make(ksx, ksy, ksz)), ld = v_luminance(v3_make(kdx, kdy, kdz));
  vfloat specProb = vsel(ls > 0.0f, ls / (ls + ld), v_f(0.0f));
  vmask packet = hit & ((v_as_uint(e2w) & (MCL_ATTR_NORMALS | MCL_ATTR_COLOR)) == 0u) & (v_as_uint(kdw) == MCL_NO_TEXTURE) &
                 (specProb == 0.0f) & (v_as_uint(kaw) == (uint)MCL_MATERIAL_diffuse) &
                 (v_as_uint(kmz) == 0u) & (v_as_uint(kmw) == 0u);  // no normal or bump map (Material::maps.z, w)
  vmask scalar = hit & v_not(packet);
  vfloat dx, dy, dz, dw;
  v_load4_stride((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, &dx, &dy, &dz, &dw);
  vfloat3 dir = v3_make(dx, dy, dz);
  vfloat3 n = v3_make(nx, ny, nz);
  // emitted_toward(n, material, dir)
  vmask front = v3_dot(n, dir) < 0.0f;
  vmask emits = front | (kew != 0.0f);
  vfloat3 le = v3_make(vsel(emits, kex, v_f(0.0f)), vsel(emits, key, v_f(0.0f)), vsel(emits, kez, v_f(0.0f)));
  v_store4(rad, vsel(hit, le.x, v_f(bg.x)), vsel(hit, le.y, v_f(bg.y)), vsel(hit, le.z, v_f(bg.z)),
           vsel(hit, v_f(0.0f), v_f(bg.w)));
  vfloat3 bo = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)), bd = v3_make(v_f(0.0f), v_f(0.0f), v_f(1.0f));
  vfloat btmax = v_f(-1.0f);
  if (v_any(packet)) {
    vfloat3 p = v3_add(v3_add(v3_make(v0x, v0y, v0z), v3_scale(v3_make(e1x, e1y, e1z), hu)),
                       v3_scale(v3_make(e2x, e2y, e2z), hv));
    vfloat3 ng = v_orient_facing(n, dir);  // flat: ns = ng
    vfloat3 kd = v3_make(kdx, kdy, kdz);
    vfloat3 origin = v_offset_ray_origin(p, ng, f->offsetScale);
    vuint pixel, sample;
    v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
    const float nLight = (float)f->lightSamples;
    const int useLight = f->directSampling != MCL_DIRECT_BRDF && f->emitterCount > 0;  // no environment here
    const int useBrdf = f->directSampling != MCL_DIRECT_LIGHT;
    vuint slot0 = (first + v_lane_index()) * slots;
    for (uint k = 0; useLight && k < f->lightSamples; ++k) {
      vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_LIGHT + k);
      // sample_direct_light without an environment (pEnv = 0): an emitter by power, a point on it.
      VEmitterSample ls = v_sample_emitter(f, a->emitters, a->tris, a->normals, a->materials, u.x, u.y, u.z, origin);
      vfloat3 wi = ls.wi, lle = ls.le;
      vfloat dist = ls.dist, pdf = ls.pdf;
      vmask ok = ls.ok;
      wi = v3_select(ok, wi, v3_make(v_f(0.0f), v_f(0.0f), v_f(1.0f)));
      lle = v3_select(ok, lle, v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)));
      vfloat tmax = vsel(ok, dist * (1.0f - 1e-4f), v_f(INFINITY));
      vfloat cosSurf = v3_dot(ng, wi);  // frame_cosine, flat
      vmask push = packet & (pdf > 0.0f) & (cosSurf > 0.0f);
      vfloat weight = v_f(1.0f);
      if (useBrdf) {  // power_heuristic(nLight, pdf, 1, bsdf_pdf): the Lambert pdf of wi
        vfloat bsdfPdf = fmax(cosSurf, v_f(0.0f)) * MCL_INV_PI;
        vfloat fw = nLight * pdf, gw = 1.0f * bsdfPdf;
        weight = v_power_heuristic(fw, gw);
      }
      vmask lit = cosSurf > 0.0f;  // bsdf_f: Kd / pi above the surface
      vfloat3 fr = v3_make(vsel(lit, kd.x * MCL_INV_PI, v_f(0.0f)), vsel(lit, kd.y * MCL_INV_PI, v_f(0.0f)),
                           vsel(lit, kd.z * MCL_INV_PI, v_f(0.0f)));
      vfloat s = cosSurf * weight / (pdf * nLight);
      vfloat3 contrib = v3_scale(v3_mul(fr, lle), s);
      v_push_shadow_queries(a->queue, a->queueCount, push, origin, wi, tmax, contrib, slot0 + k);
    }
    if (useBrdf) {  // Lambertian: the cosine lobe around ng
      vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_BRDF);
      vfloat3 wi = v_to_world(v_sample_cosine_hemisphere(u.x, u.y), ng);
      bo = v3_select(packet, origin, bo);
      bd = v3_select(packet, wi, bd);
      btmax = vsel(packet, v_f(INFINITY), btmax);
    }
  }
  v_store4_stride(bounce, 8, bo.x, bo.y, bo.z, v_f(0.0f));
  v_store4_stride(bounce + 4, 8, bd.x, bd.y, bd.z, btmax);
  if (v_any(scalar)) {
    uint s[MCL_LANES] MCL_LANE_ALIGN;
    v_store_lanes(v_mask01(scalar), s);
    for (uint k = 0; k < MCL_LANES; ++k)
      if (s[k]) stage_shade_direct(a, first + k);
  }
}
