// shade_path: one bounce of the path tracer for each live path k < *rayCount (its ray rays[k],
// hit hits[k], id pathIds[k], the identity at bounce 0). Reads and writes the path's state by id:
// radiance[id] (accumulated L) and throughput[id] (rgb: the path weight; w: solid-angle pdf of the
// BSDF sample that made the ray, 0 for camera rays and after a delta lobe: no MIS). Adds emission seen (MIS-weighted against
// light sampling after a BSDF bounce) or the miss radiance, pushes lightSamples
// next-event queries onto the shadow queue (slots id * shadowSlots + k, contributions MIS
// weighted but for delta lights; lights: emitter triangles, the environment and the light records,
// stages/direct_light.h), samples the
// BSDF (lane_frame, stage_lanes.h: the material kind's BSDF around the shading frame;
// textures filtered with the camera's ray-cone width at this segment's length, a lower bound after
// diffuse bounces), applies Russian roulette from depth
// rrDepth, and pushes the continuation ray onto nextRays / nextPathIds (compacted, *nextCount).
// Depth (Mitsuba's convention, FrameParams::maxDepth D): hit b adds emission when b < D, next-event
// estimation and a continuation when b + 1 < D; D = -1 is unlimited. Random numbers: bounce b
// owns dimension groups MCL_DIM_PATH + b * MCL_DIM_PATH_STRIDE + j (rng.h).
// The body takes W consecutive queue entries, one per lane (W = MCL_LANES: 1 on the host backend
// and GPUs; lanes past the queue masked; per-path state gathered and scattered by id). Misses: the
// background at bounce 0 without an environment, else the environment in lanes (camera rays see
// it unweighted; after a BSDF bounce it is MIS weighted against environment sampling with the BSDF
// sample's pdf). Emission seen (MIS weighted after a BSDF bounce) for every
// hit in lanes (an emission texture and its emitter weight too: lane_hit_emission). Hits on every material
// kind (lane_bsdf.h), textured or not, flat or smooth, in lanes (the frame, the metallic-roughness
// texture, glTF transmission's kind pick, normal and bump maps, instances: lane_frame in
// stage_lanes.h): the next-event light samples (the light kind picked per lane: emitter
// triangles, point, spot, directional and sun lights and the environment in lanes,
// lane_lights.h;
// one atomic per packet per light sample; a light below the geometric surface through a
// transmitting lobe, its shadow ray from the far side) and the BSDF continuation with Russian
// roulette (one atomic per packet).
// Queue order: the packet's shadow queries and continuations fill their entries in lane order, so
// the next queue's order depends on W; nothing depends on it (shadow queries name their slot,
// path_gather adds slots in slot order, every random number comes from the path's pixel and
// sample, and the path's state is indexed by its id).
#pragma once
#include "stage_lanes.h"
#include "lane_bsdf.h"
#include "lane_lights.h"
#include "direct_light.h"

MCL_INLINE uint path_dim(uint bounce, uint j) { return MCL_DIM_PATH + bounce * MCL_DIM_PATH_STRIDE + j; }

MCL_INLINE vfloat v_max_component(vfloat3 c) { return fmax(c.x, fmax(c.y, c.z)); }

MCL_INLINE void stage_shade_path(const shade_path_args* a, uint first) {
  const uint count = *a->rayCount;
  if (first >= count) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint bounce = a->pathBounce;
  const uint slots = f->shadowSlots;
  LightScene lights = make_light_scene(a->tris, a->normals, a->materials, a->emitters, a->envMap, a->envCdf,
                                       a->lightRecords, a->shading,
                                       make_texture_tables(a->textures, a->textureLevels, a->texels));
  const uint lanes = v_packet_lanes(first, count);
  const vmask own = v_lane_index() < lanes;  // the lanes with an entry
  // Lanes past the queue repeat its last entry (masked).
  vuint at = vsel(own, v_lane_index(), v_u(lanes - 1u));
  vuint id = bounce == 0 ? first + at
                         : (lanes == MCL_LANES ? v_load_uints(a->pathIds + first) : v_gather_uint(a->pathIds + first, at));
  vfloat ht, htri, hu, hv;
  v_load4_n((MCL_GLOBAL const float*)(a->hits + first), lanes, &ht, &htri, &hu, &hv);
  vuint tri = v_as_uint(htri);
  vmask hit = own & (tri != MCL_NO_HIT);
  // The hit triangles, their materials, and the lanes taken in lane types (kinds: lane_bsdf.h's)
  // and from the triangle alone (flat).
  LaneHits lh = lane_hits(f, a->tris, a->normals, a->materials, a->hitInstances, first, lanes, hit, tri);
  const vmask kinds = lane_bsdf_kinds(&lh), flat = lh.flat;
  lane_tally(f, a->packedLanes, a->aloneLanes, kinds, hit);

  uint ids[MCL_LANES] MCL_LANE_ALIGN, owned[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(id, ids);
  v_store_lanes(v_mask01(own), owned);
  for (uint j = 0; j < MCL_LANES; ++j)
    if (owned[j])
      for (uint s = 0; s < slots; ++s) a->shadowContrib[ids[j] * slots + s] = make_float4(0.0f, 0.0f, 0.0f, 0.0f);

  vfloat3 beta = v3_make(v_f(1.0f), v_f(1.0f), v_f(1.0f)), L = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
  vfloat lastPdf = v_f(0.0f);
  if (bounce > 0) {
    vfloat lw;
    v_gather4((MCL_GLOBAL const float*)a->throughput, id, 4, &beta.x, &beta.y, &beta.z, &lastPdf);
    v_gather4((MCL_GLOBAL const float*)a->radiance, id, 4, &L.x, &L.y, &L.z, &lw);
  }
  vfloat dx, dy, dz, dw;
  v_load4_stride_n((MCL_GLOBAL const float*)(a->rays + first) + 4, 8, lanes, &dx, &dy, &dz, &dw);
  vfloat3 dir = v3_make(dx, dy, dz);
  vfloat3 n = lh.n;
  const float nLight = (float)f->lightSamples;

  // Misses: without an environment the background at bounce 0, else nothing.
  vfloat3 miss;
  if (!env_present(f)) {
    float4 bg = bounce == 0 ? f->background : make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    miss = v3_make(v_f(bg.x), v_f(bg.y), v_f(bg.z));
  } else {  // the environment (environment_light_eval_of), MIS weighted after a BSDF bounce
    miss = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
    if (v_any(own & v_not(hit))) {
      miss = v_environment_light_eval_of(f, lights, dir);
      if (bounce > 0) {
        vfloat w = v_power_heuristic_of(1.0f * lastPdf, nLight * v_environment_light_pdf_of(f, lights, dir));
        miss = v3_select(lastPdf > 0.0f, v3_scale(miss, w), miss);
      }
    }
  }
  vfloat3 Lmiss = v3_add(L, v3_mul(beta, miss));
  // Hits: Le seen (area_light_eval: emitted_toward), MIS weighted against light sampling after a
  // BSDF bounce (area_light_pdf).
  vmask front = v3_dot(n, dir) < 0.0f;
  vmask emits = front | (lh.twoSided != 0.0f);
  vfloat3 ke = lh.ke;
  vfloat keLum = v_luminance(lh.ke);  // emitter_luminance
  if (f->emissionTextured) ke = lane_hit_emission(lights, &lh, hit, hu, hv, &keLum);
  vfloat3 le = v3_make(vsel(emits, ke.x, v_f(0.0f)), vsel(emits, ke.y, v_f(0.0f)), vsel(emits, ke.z, v_f(0.0f)));
  vmask glows = hit & ((le.x > 0.0f) | (le.y > 0.0f) | (le.z > 0.0f));
  if (v_any(glows)) {
    vfloat weight = v_f(1.0f);
    if (bounce > 0 && f->emitterCount > 0u) {
      vfloat lpdf = area_light_probability(f) *
                    v_area_pdf_of(f, lh.area, keLum, ht * ht, v_emitter_cosine_of(n, lh.twoSided, dir));
      vfloat fw = 1.0f * lastPdf, gw = nLight * lpdf;
      weight = vsel(lastPdf > 0.0f, v_power_heuristic_of(fw, gw), weight);
    }
    L = v3_select(glows, v3_add(L, v3_scale(v3_mul(beta, le), weight)), L);
  }
  L = v3_select(hit, L, Lmiss);
  {
    float lx[MCL_LANES] MCL_LANE_ALIGN, ly[MCL_LANES] MCL_LANE_ALIGN, lz[MCL_LANES] MCL_LANE_ALIGN;
    v3_store_lanes(L, lx, ly, lz);
    for (uint j = 0; j < MCL_LANES; ++j)
      if (owned[j]) a->radiance[ids[j]] = make_float4(lx[j], ly[j], lz[j], 0.0f);
  }

  if ((f->maxDepth < 0 || (int)bounce + 1 < f->maxDepth) && v_any(hit)) {
    vuint pixel, sample;
    if (!v_items_pixel_sample(f, a->active, a->waveStart, id, &pixel, &sample)) {
      uint px[MCL_LANES] MCL_LANE_ALIGN, sm[MCL_LANES] MCL_LANE_ALIGN;
      for (uint j = 0; j < MCL_LANES; ++j) {
        px[j] = item_pixel(f, a->active, a->waveStart, ids[j]);
        sm[j] = item_sample(f, a->waveStart, ids[j]);
      }
      pixel = v_loadu_lanes(px);
      sample = v_loadu_lanes(sm);
    }
    LaneFrame sf =
        lane_frame(MCL_STAGE_SURFACE_SCENE(a), f, kinds & v_not(flat), pixel, sample, bounce, &lh, hu, hv, ht, dir);
    vfloat3 origin = v_offset_ray_origin(sf.p, sf.ng, f->offsetScale);
    const LaneBsdf lb = lane_bsdf(&lh, sf);
    const vfloat3 wo = v3_neg(dir);
    // Light samples where some light exists and the BSDF is not purely delta (every light direction
    // has f = 0 there; the emitter its BSDF sample finds counts fully).
    const int nee = f->emitterCount > 0u || env_present(f) || f->lightCount > 0u;
    const vmask takes = kinds & v_not(lane_bsdf_delta(&lb));
    vuint slot0 = id * slots;
    for (uint s = 0; nee && v_any(takes) && s < f->lightSamples; ++s) {
      vfloat4 u = v_sample_uniform4(f, pixel, sample, path_dim(bounce, 1u + s));
      VLightSample ls = v_sample_direct_light(f, lights, takes, origin, u);
      vfloat3 wi = ls.wi, lle = ls.le;
      vfloat pdf = ls.pdf, tmax = ls.tmax;
      vmask delta = ls.delta;
      vfloat bsdfPdf;
      vfloat3 fcos = lane_bsdf_eval_pdf(&lb, sf, wo, wi, &bsdfPdf);
      vmask push = takes & (pdf > 0.0f) & (v_max_component(fcos) > 0.0f);
      if (!v_any(push)) continue;
      vfloat fw = nLight * pdf, gw = 1.0f * bsdfPdf;
      vfloat weight = vsel(delta, v_f(1.0f), v_power_heuristic_of(fw, gw));
      vfloat3 contrib = v3_scale(v3_mul(v3_mul(beta, fcos), lle), weight / (pdf * nLight));
      // A light below the geometric surface (seen through a transmitting lobe): the shadow ray
      // leaves from the far side.
      vfloat3 from, along;
      vfloat reach;
      lane_shadow_query(sf, f->offsetScale, push & v_not(v3_dot(sf.ng, wi) > 0.0f), origin, wi, tmax, &from, &along,
                        &reach);
      v_push_shadow_queries(a->queue, a->queueCount, push, from, along, reach, contrib, slot0 + s);
    }

    // bsdf_sample, Russian roulette from depth rrDepth, the continuation ray.
    vfloat4 u = v_sample_uniform4(f, pixel, sample, path_dim(bounce, 0u));  // z: roulette, w: lobe
    const vBsdfSample bs = lane_bsdf_sample(&lb, sf, wo, u.x, u.y, u.w);
    vfloat3 wi = bs.wi;
    vfloat pdf = bs.pdf;
    vmask live = kinds & (pdf > 0.0f);
    vfloat3 next = v3_mul(beta, bs.weight);
    if (bounce + 1u >= f->rrDepth) {  // Russian roulette (depth after this bounce: bounce + 1)
      vfloat q = fmin(v_f(0.95f), v_max_component(next));
      live = live & (u.z < q);
      next = v3_make(next.x / q, next.y / q, next.z / q);
    }
    live = live & (v_max_component(next) > 0.0f);
    if (v_any(live)) {
      // w: the sample's pdf for MIS at the next hit, 0 after a delta lobe; a transmitted ray
      // starts on the far side.
      pdf = vsel((bs.flags & MCL_BSDF_DELTA) != 0, v_f(0.0f), pdf);
      vmask through = live & ((bs.flags & MCL_BSDF_TRANSMISSION) != 0);
      if (v_any(through)) origin = v3_select(through, v_offset_ray_origin(sf.p, v3_neg(sf.ng), f->offsetScale), origin);
      uint set[MCL_LANES] MCL_LANE_ALIGN;
      float ox[MCL_LANES] MCL_LANE_ALIGN, oy[MCL_LANES] MCL_LANE_ALIGN, oz[MCL_LANES] MCL_LANE_ALIGN;
      float wx[MCL_LANES] MCL_LANE_ALIGN, wy[MCL_LANES] MCL_LANE_ALIGN, wz[MCL_LANES] MCL_LANE_ALIGN;
      float bx[MCL_LANES] MCL_LANE_ALIGN, by[MCL_LANES] MCL_LANE_ALIGN, bz[MCL_LANES] MCL_LANE_ALIGN;
      float pp[MCL_LANES] MCL_LANE_ALIGN;
      v_store_lanes(v_mask01(live), set);
      v3_store_lanes(origin, ox, oy, oz);
      v3_store_lanes(wi, wx, wy, wz);
      v3_store_lanes(next, bx, by, bz);
      v_store_lanes(pdf, pp);
      uint at = MCL_ATOMIC_ADD(a->nextCount, v_count(live));
      for (uint j = 0; j < MCL_LANES; ++j) {
        if (!set[j]) continue;
        a->throughput[ids[j]] = make_float4(bx[j], by[j], bz[j], pp[j]);
        Ray r;
        r.origin = make_float4(ox[j], oy[j], oz[j], 0.0f);
        r.dir = make_float4(wx[j], wy[j], wz[j], INFINITY);
        a->nextRays[at] = r;
        a->nextPathIds[at] = ids[j];
        ++at;
      }
    }
  }
}
