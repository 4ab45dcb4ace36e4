// shade_direct: reads camera rays, hits, materials, the emitter table, the environment, the
// attribute buffer and textures; for camera item i writes radiance[i] (on a miss the environment,
// or the background without one; else Le seen directly), pushes K light-sample occlusion queries
// onto the shadow queue (light / mis; lights: the environment, emitter triangles and the light
// records: point, spot, directional, the delta ones by light sampling only; stages/direct_light.h) and writes the BSDF ray bounce[i] (brdf / mis; otherwise an empty ray
// with tmax < 0). Surfaces: lane_frame (stage_lanes.h): the shading frame and the material
// kind's BSDF (shared/bsdf.h; light directions below the geometric surface count only through a
// transmitting lobe, their shadow rays leaving from the far side).
// Shadow slots per sample: [0, K) light samples, K the BSDF sample (shade_direct_hit); each
// strategy leaves the slots it does not use at 0.
// The body takes W consecutive camera hits, one per lane (W = MCL_LANES: 1 on the host backend
// and GPUs; lanes past the wave masked): misses (the background, or the environment in lanes)
// and hits on every material kind (lane_bsdf.h), textured or not, flat or
// smooth, in lanes (stage_lanes.h: the frame, albedo, metallic-roughness texture and glTF
// transmission's kind pick, normal and bump maps, instances: lane_frame in lanes): Le seen, the
// light samples (the light kind picked per lane, emitter triangles, point, spot, directional
// and sun lights and the environment in lanes, lane_lights.h; one atomic per packet per light sample; the Lambertian lobe's Kd / pi spelled out, the other kinds' f cos, a light
// below the surface through a transmitting lobe with its shadow ray from the far side) and the
// BSDF ray (the cosine lobe, folded where smooth; the other kinds' sample). Emission textures and
// BLEND emitters in lanes too (lane_hit_emission, v_area_light_at).
#pragma once
#include "stage_lanes.h"
#include "lane_bsdf.h"
#include "lane_lights.h"
#include "direct_light.h"

MCL_INLINE void stage_shade_direct(const shade_direct_args* a, uint first) {
  if (first >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint lanes = v_packet_lanes(first, a->waveCount);
  const vmask own = v_lane_index() < lanes;  // the lanes with an item
  vfloat ht, htri, hu, hv;
  v_load4_n((MCL_GLOBAL const float*)(a->hits + first), lanes, &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = own & (tri != MCL_NO_HIT);
  const uint slots = f->shadowSlots;
  for (uint k = 0; k < lanes * slots; ++k)  // the strategies leave the slots they do not use at 0
    a->shadowContrib[first * slots + k] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  float4 bg = f->background;
  MCL_GLOBAL float* rad = (MCL_GLOBAL float*)(a->radiance + first);
  MCL_GLOBAL float* bounce = (MCL_GLOBAL float*)(a->bounce + first);
  const int env = env_present(f);
  if (!v_any(hit) && !env) {
    v_store4_n(rad, lanes, v_f(bg.x), v_f(bg.y), v_f(bg.z), v_f(bg.w));
    v_store4_stride_n(bounce, 8, lanes, v_f(0.0f), v_f(0.0f), v_f(0.0f), v_f(0.0f));
    v_store4_stride_n(bounce + 4, 8, lanes, v_f(0.0f), v_f(0.0f), v_f(1.0f), v_f(-1.0f));
    return;
  }
  // The hit triangles, their materials, and the lanes taken in lane types (kinds: lane_bsdf.h's;
  // packet: the Lambertian lobe's, rest: the other kinds') and from the triangle alone (flat).
  LaneHits lh = lane_hits(f, a->tris, a->normals, a->materials, a->hitInstances, first, lanes, hit, tri);
  const vmask kinds = lane_bsdf_kinds(&lh), packet = lh.lamb, rest = kinds & v_not(lh.lamb), flat = lh.flat;
  lane_tally(f, a->packedLanes, a->aloneLanes, kinds, hit);
  vfloat dx, dy, dz, dw;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  vfloat3 dir = v3_make(dx, dy, dz);
  vfloat3 n = lh.n;
  // emitted_toward(n, material, dir)
  vmask front = v3_dot(n, dir) < 0.0f;
  vmask emits = front | (lh.twoSided != 0.0f);
  LightScene lights = make_light_scene(a->tris, a->normals, a->materials, a->emitters, a->envMap, a->envCdf,
                                       a->lightRecords, a->shading,
                                       make_texture_tables(a->textures, a->textureLevels, a->texels));
  vfloat3 miss = v3_make(v_f(bg.x), v_f(bg.y), v_f(bg.z));
  vfloat missW = v_f(bg.w);
  if (env) {  // the environment seen (environment_light_eval_of)
    if (v_any(own & v_not(hit))) miss = v_environment_light_eval_of(f, lights, dir);
    missW = v_f(0.0f);
  }
  vfloat3 ke = lh.ke;
  if (f->emissionTextured) ke = lane_hit_emission(lights, &lh, hit, hu, hv, 0);  // no MIS weight for camera rays
  vfloat3 le = v3_make(vsel(emits, ke.x, v_f(0.0f)), vsel(emits, ke.y, v_f(0.0f)), vsel(emits, ke.z, v_f(0.0f)));
  v_store4_n(rad, lanes, vsel(hit, le.x, miss.x), vsel(hit, le.y, miss.y), vsel(hit, le.z, miss.z), vsel(hit, v_f(0.0f), missW));
  vfloat3 bo = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)), bd = v3_make(v_f(0.0f), v_f(0.0f), v_f(1.0f));
  vfloat btmax = v_f(-1.0f);
  if (v_any(hit)) {
    vuint pixel, sample;
    v_item_pixel_sample(f, a->active, a->waveStart, first, &pixel, &sample);
    LaneFrame sf =
        lane_frame(MCL_STAGE_SURFACE_SCENE(a), f, kinds & v_not(flat), pixel, sample, 0u, &lh, hu, hv, ht, dir);
    vfloat3 origin = v_offset_ray_origin(sf.p, sf.ng, f->offsetScale);
    const LaneBsdf lb = lane_bsdf(&lh, sf);
    const vfloat3 wo = v3_neg(dir);
    // Light samples (light / mis) at the other kinds where the BSDF is not purely delta: light
    // sampling at a mirror or smooth glass finds nothing (f = 0 for every light direction), the
    // BSDF ray (shade_direct_hit) carries it all.
    const vmask restLit = rest & v_not(lane_bsdf_delta(&lb));
    const float nLight = (float)f->lightSamples;
    const int useLight = f->directSampling != MCL_DIRECT_BRDF && (f->emitterCount > 0 || env || f->lightCount > 0u);
    const int useBrdf = f->directSampling != MCL_DIRECT_LIGHT;
    vuint slot0 = (first + v_lane_index()) * slots;
    for (uint k = 0; useLight && v_any(packet | restLit) && k < f->lightSamples; ++k) {
      vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_LIGHT + k);
      VLightSample ls = v_sample_direct_light(f, lights, packet | restLit, origin, u);
      vfloat3 wi = ls.wi, lle = ls.le;
      vfloat pdf = ls.pdf, tmax = ls.tmax;
      vmask delta = ls.delta;
      // frame_cosine; a Lambertian surface sees nothing below the geometric surface.
      vmask above = v3_dot(sf.ng, wi) > 0.0f;
      vfloat cn = v3_dot(sf.ns, wi);
      vfloat cosSurf = vsel(sf.smooth, vsel(above, fmax(cn, v_f(0.0f)), v_f(0.0f)), cn);
      vmask push = packet & (pdf > 0.0f) & above & (cosSurf > 0.0f);
      vfloat3 from = origin, along = wi;  // the Lambertian lobe's queries (above the surface)
      vfloat reach = tmax;
      vfloat3 contrib = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
      if (v_any(restLit)) {  // direct_light_sample: f cos above the surface, the BSDF's own f |cos| below
        vfloat bsdfPdf;
        vfloat3 fcos = lane_bsdf_eval_pdf(&lb, sf, wo, wi, &bsdfPdf);
        vmask below = v_not(above);
        vfloat3 fcosBelow = v3_select(below, fcos, v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)));
        vmask lit = restLit & (pdf > 0.0f) &
                    vsel(below, fmax(fcosBelow.x, fmax(fcosBelow.y, fcosBelow.z)) > 0.0f, cosSurf > 0.0f);
        if (v_any(lit)) {
          vfloat weight = v_f(1.0f);
          if (useBrdf) weight = vsel(delta, weight, v_power_heuristic_of(nLight * pdf, 1.0f * bsdfPdf));
          vfloat3 cb = v3_scale(v3_mul(fcosBelow, lle), weight / (pdf * nLight));
          vfloat3 ca = v3_scale(v3_mul(lane_bsdf_f(&lb, sf, wo, wi), lle), cosSurf * weight / (pdf * nLight));
          contrib = v3_select(lit, v3_select(below, cb, ca), contrib);
          lane_shadow_query(sf, f->offsetScale, lit & below, origin, wi, tmax, &from, &along, &reach);
          push = push | lit;
        }
      }
      if (!v_any(push)) continue;
      vfloat weight = v_f(1.0f);
      if (useBrdf) {  // power_heuristic(nLight, pdf, 1, bsdf_pdf), none for a delta light
        vfloat fw = nLight * pdf, gw = 1.0f * v_lambert_pdf(sf.ng, sf.ns, sf.smooth, wi);
        weight = vsel(delta, weight, v_power_heuristic_of(fw, gw));
      }
      vmask lit = above & (cn > 0.0f);  // bsdf_f: Kd / pi above the surface
      vfloat3 fr = v3_make(vsel(lit, sf.kd.x * MCL_INV_PI, v_f(0.0f)), vsel(lit, sf.kd.y * MCL_INV_PI, v_f(0.0f)),
                           vsel(lit, sf.kd.z * MCL_INV_PI, v_f(0.0f)));
      vfloat s = cosSurf * weight / (pdf * nLight);
      contrib = v3_select(packet, v3_scale(v3_mul(fr, lle), s), contrib);
      v_push_shadow_queries(a->queue, a->queueCount, push, from, along, reach, contrib, slot0 + k);
    }
    if (useBrdf) {  // Lambertian: the cosine lobe around ns, folded above ng where smooth
      vfloat4 u = v_sample_uniform4(f, pixel, sample, MCL_DIM_BRDF);
      vfloat3 w = v_to_world(v_sample_cosine_hemisphere(u.x, u.y), sf.ns);
      vfloat d = v3_dot(w, sf.ng);  // fold_above
      vfloat3 wi = v3_select(sf.smooth & (d < 0.0f), v3_sub(w, v3_scale(sf.ng, 2.0f * d)), w);
      bo = v3_select(packet, origin, bo);
      bd = v3_select(packet, wi, bd);
      btmax = vsel(packet, v_f(INFINITY), btmax);
      if (v_any(rest)) {  // direct_bsdf_ray: the kind's sample, traced where its pdf is positive
        vBsdfSample q = lane_bsdf_sample(&lb, sf, wo, u.x, u.y, u.z);
        vmask traced = rest & (q.pdf > 0.0f);
        vmask through = traced & ((q.flags & MCL_BSDF_TRANSMISSION) != 0);
        vfloat3 o = origin;
        if (v_any(through)) o = v3_select(through, v_offset_ray_origin(sf.p, v3_neg(sf.ng), f->offsetScale), o);
        bo = v3_select(traced, o, bo);
        bd = v3_select(traced, q.wi, bd);
        btmax = vsel(traced, v_f(INFINITY), btmax);
      }
    }
  }
  v_store4_stride_n(bounce, 8, lanes, bo.x, bo.y, bo.z, v_f(0.0f));
  v_store4_stride_n(bounce + 4, 8, lanes, bd.x, bd.y, bd.z, btmax);
}
