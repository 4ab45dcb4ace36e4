// shade_direct_lanes.h: the packet form of shade_direct (shade_direct.h) for the common case, the
// same bits per item: W consecutive camera hits, one per lane, on flat (no shading normals),
// untextured, Lambertian surfaces of the diffuse kind (no glossy lobe) lit by emitter triangles: Le seen directly, the
// light samples (an emitter by power, a uniform point on it; one atomic per packet per light
// sample) and the BSDF ray (cosine lobe). Lanes that hit anything else (shading normals, an albedo
// texture, a glossy lobe) run the scalar body after the packet; so does every item of a packet
// when an environment lights the scene, and of a partial last packet.
#pragma once
#include "shade_direct.h"
#include "stage_lanes.h"

// luminance (lights.h) per lane.
MCL_INLINE vfloat v_luminance(vfloat3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// pick_emitter per lane: the first emitter whose cdf exceeds u (binary search, lanes masked as
// they finish); count > 0.
MCL_INLINE vuint v_pick_emitter(MCL_GLOBAL const Emitter* emitters, uint count, vfloat u) {
  vuint lo = v_u(0u), hi = v_u(count - 1u);
  MCL_GLOBAL const float* cdf = (MCL_GLOBAL const float*)emitters + 1;  // Emitter::cdf
  for (;;) {
    vmask active = lo < hi;
    if (!v_any(active)) break;
    vuint mid = (lo + hi) / 2u;
    vmask above = v_gather_float(cdf, vsel(active, mid, lo), 4) > u;
    hi = vsel(active & above, mid, hi);
    lo = vsel(active & v_not(above), mid + 1u, lo);
  }
  return lo;
}

MCL_INLINE void stage_shade_direct_lanes(const shade_direct_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  if (v_packet_partial(first, a->waveCount) || env_present(f)) {
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
  v_gather4(mf, mat, 16, &kdx, &kdy, &kdz, &kdw);      // albedo: Kd, texture index
  v_gather4(mf + 4, mat, 16, &kex, &key, &kez, &kew);  // emission: Ke, two-sided
  v_gather4(mf + 8, mat, 16, &ksx, &ksy, &ksz, &ksw);  // specular: Ks, alpha
  vfloat kax, kay, kaz, kaw;
  v_gather4(mf + 12, mat, 16, &kax, &kay, &kaz, &kaw);  // alpha test; w: the material kind (uint bits)
  // bsdf_make's specProb, as the scalar body computes it: the packet takes the lanes where it is 0.
  vfloat ls = v_luminance(v3_make(ksx, ksy, ksz)), ld = v_luminance(v3_make(kdx, kdy, kdz));
  vfloat specProb = vsel(ls > 0.0f, ls / (ls + ld), v_f(0.0f));
  vmask packet = hit & ((v_as_uint(e2w) & MCL_ATTR_NORMALS) == 0u) & (v_as_uint(kdw) == MCL_NO_TEXTURE) &
                 (specProb == 0.0f) & (v_as_uint(kaw) == (uint)MCL_MATERIAL_diffuse);
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
      vfloat4 u = v_rng_uniform4(f->seed, pixel, sample, MCL_DIM_LIGHT + k);
      // sample_direct_light without an environment (pEnv = 0): an emitter by power, a point on it.
      vuint em = v_pick_emitter(a->emitters, f->emitterCount, u.x);
      vfloat emTri, emCdf, emArea, emPad;
      v_gather4_few((MCL_GLOBAL const float*)a->emitters, em, 4, &emTri, &emCdf, &emArea, &emPad);
      vuint lt = v_as_uint(emTri);
      vfloat l0x, l0y, l0z, l0w, l1x, l1y, l1z, l1w, l2x, l2y, l2z, l2w, lnx, lny, lnz, lnw;
      v_gather4_few(tf, lt, 12, &l0x, &l0y, &l0z, &l0w);
      v_gather4_few(tf + 4, lt, 12, &l1x, &l1y, &l1z, &l1w);
      v_gather4_few(tf + 8, lt, 12, &l2x, &l2y, &l2z, &l2w);
      v_gather4_few((MCL_GLOBAL const float*)a->normals, lt, 4, &lnx, &lny, &lnz, &lnw);
      vfloat lex, ley, lez, lew;
      v_gather4_few(mf + 4, v_as_uint(l0w), 16, &lex, &ley, &lez, &lew);
      vfloat3 lle = v3_make(lex, ley, lez);
      // sample_triangle
      vfloat su = sqrt(u.y);
      vfloat3 lp = v3_add(v3_add(v3_make(l0x, l0y, l0z), v3_scale(v3_make(l1x, l1y, l1z), su * (1.0f - u.z))),
                          v3_scale(v3_make(l2x, l2y, l2z), su * u.z));
      vfloat3 toLight = v3_sub(lp, origin);
      vfloat dist2 = v3_dot(toLight, toLight);
      vfloat dist = sqrt(dist2);
      vfloat3 wi = v3_make(toLight.x / dist, toLight.y / dist, toLight.z / dist);
      vfloat c = -v3_dot(v3_make(lnx, lny, lnz), wi);  // emitter_cosine
      vfloat cosLight = vsel(lew != 0.0f, fabs(c), c);
      vmask ok = (cosLight > 0.0f) & (dist > 0.0f);
      vfloat pick = emArea * v_luminance(lle) / f->emitterPower;  // emitter_pick_probability
      vfloat pdf = vsel(ok, pick / emArea * dist2 / cosLight, v_f(0.0f));  // area_to_solid_angle
      wi = v3_select(ok, wi, v3_make(v_f(0.0f), v_f(0.0f), v_f(1.0f)));
      lle = v3_select(ok, lle, v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)));
      vfloat tmax = vsel(ok, dist * (1.0f - 1e-4f), v_f(INFINITY));
      vfloat cosSurf = v3_dot(ng, wi);  // frame_cosine, flat
      vmask push = packet & (pdf > 0.0f) & (cosSurf > 0.0f);
      vfloat weight = v_f(1.0f);
      if (useBrdf) {  // power_heuristic(nLight, pdf, 1, bsdf_pdf): the Lambert pdf of wi
        vfloat bsdfPdf = fmax(cosSurf, v_f(0.0f)) * MCL_INV_PI;
        vfloat fw = nLight * pdf, gw = 1.0f * bsdfPdf;
        weight = (fw * fw) / (fw * fw + gw * gw);
      }
      vmask lit = cosSurf > 0.0f;  // bsdf_f: Kd / pi above the surface
      vfloat3 fr = v3_make(vsel(lit, kd.x * MCL_INV_PI, v_f(0.0f)), vsel(lit, kd.y * MCL_INV_PI, v_f(0.0f)),
                           vsel(lit, kd.z * MCL_INV_PI, v_f(0.0f)));
      vfloat s = cosSurf * weight / (pdf * nLight);
      vfloat3 contrib = v3_scale(v3_mul(fr, lle), s);
      // tmax of a sample through the shadow queue is per lane: pushed lane by lane below.
      uint set[MCL_LANES] MCL_LANE_ALIGN;
      float tm[MCL_LANES] MCL_LANE_ALIGN;
      v_store_lanes(v_mask01(push), set);
      v_store_lanes(tmax, tm);
      uint count = v_count(push);
      if (count == 0) continue;
      uint at = MCL_ATOMIC_ADD(a->queueCount, count);
      float ox[MCL_LANES] MCL_LANE_ALIGN, oy[MCL_LANES] MCL_LANE_ALIGN, oz[MCL_LANES] MCL_LANE_ALIGN;
      float wx[MCL_LANES] MCL_LANE_ALIGN, wy[MCL_LANES] MCL_LANE_ALIGN, wz[MCL_LANES] MCL_LANE_ALIGN;
      float cr[MCL_LANES] MCL_LANE_ALIGN, cg[MCL_LANES] MCL_LANE_ALIGN, cb[MCL_LANES] MCL_LANE_ALIGN;
      uint sl[MCL_LANES] MCL_LANE_ALIGN;
      v_store_lanes(origin.x, ox);
      v_store_lanes(origin.y, oy);
      v_store_lanes(origin.z, oz);
      v_store_lanes(wi.x, wx);
      v_store_lanes(wi.y, wy);
      v_store_lanes(wi.z, wz);
      v_store_lanes(contrib.x, cr);
      v_store_lanes(contrib.y, cg);
      v_store_lanes(contrib.z, cb);
      v_store_lanes(slot0 + k, sl);
      for (uint j = 0; j < MCL_LANES; ++j) {
        if (!set[j]) continue;
        ShadowWork w;
        w.ray.origin = make_float4(ox[j], oy[j], oz[j], 0.0f);
        w.ray.dir = make_float4(wx[j], wy[j], wz[j], tm[j]);
        w.r = cr[j];
        w.g = cg[j];
        w.b = cb[j];
        w.slot = sl[j];
        a->queue[at++] = w;
      }
    }
    if (useBrdf) {  // Lambertian: the cosine lobe around ng
      vfloat4 u = v_rng_uniform4(f->seed, pixel, sample, MCL_DIM_BRDF);
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
