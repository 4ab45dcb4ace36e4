// lambert_lanes.h: a packet's Lambertian surfaces (the diffuse kind without a glossy lobe), per
// lane: the shading frame and albedo of each lane's hit (LaneFrame: from the triangle alone for
// flat untextured world-space hits, else from the scalar surface_at, so textures, vertex colours,
// shading normals, normal and bump maps and instances are the scalar code's), and diffuse_eval / diffuse_pdf /
// diffuse_sample of bsdf_diffuse.h with specProb 0 around that frame, the scalar operations in the
// same order per lane (shading.h's folding rule where a lane is smooth). Reads the hit buffers and
// the scene's surface tables; writes nothing.
#pragma once
#include "stage_lanes.h"

// The shading frame of W hits (SurfaceFrame per lane) and their Lambertian albedo Kd.
typedef struct {
  vfloat3 p, ng, ns, kd;
  vmask smooth;  // set where ns came from normals or a map (shading.h's folding rule applies)
} LaneFrame;

// The lanes set in `rich` of a frame whose other lanes are already set: each through the scalar
// surface_at (in its hit's instance, hit_instance), for sample ref (pixel, sample, bounce) of the
// lane; their BSDF is the diffuse kind without a glossy lobe (the caller's mask says so from the
// material).
MCL_INLINE LaneFrame lane_frame_rich(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const Hit* hits,
                                     MCL_GLOBAL const uint* hitInstances, MCL_GLOBAL const Ray* rays, uint first,
                                     vmask rich, vuint pixel, vuint sample, uint bounce, LaneFrame lf) {
  uint set[MCL_LANES] MCL_LANE_ALIGN, px[MCL_LANES] MCL_LANE_ALIGN, sm[MCL_LANES] MCL_LANE_ALIGN;
  uint smo[MCL_LANES] MCL_LANE_ALIGN;
  float pX[MCL_LANES] MCL_LANE_ALIGN, pY[MCL_LANES] MCL_LANE_ALIGN, pZ[MCL_LANES] MCL_LANE_ALIGN;
  float gX[MCL_LANES] MCL_LANE_ALIGN, gY[MCL_LANES] MCL_LANE_ALIGN, gZ[MCL_LANES] MCL_LANE_ALIGN;
  float sX[MCL_LANES] MCL_LANE_ALIGN, sY[MCL_LANES] MCL_LANE_ALIGN, sZ[MCL_LANES] MCL_LANE_ALIGN;
  float kX[MCL_LANES] MCL_LANE_ALIGN, kY[MCL_LANES] MCL_LANE_ALIGN, kZ[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(v_mask01(rich), set);
  v_store_lanes(pixel, px);
  v_store_lanes(sample, sm);
  v3_store_lanes(lf.p, pX, pY, pZ);
  v3_store_lanes(lf.ng, gX, gY, gZ);
  v3_store_lanes(lf.ns, sX, sY, sZ);
  v3_store_lanes(lf.kd, kX, kY, kZ);
  v_store_lanes(v_mask01(lf.smooth), smo);
  for (uint j = 0; j < MCL_LANES; ++j) {
    if (!set[j]) continue;
    Surface s = surface_at(sc, f, hits[first + j], hit_instance(f, hitInstances, first + j), xyz(rays[first + j].dir),
                           sample_ref(px[j], sm[j], bounce));
    pX[j] = s.frame.p.x; pY[j] = s.frame.p.y; pZ[j] = s.frame.p.z;
    gX[j] = s.frame.ng.x; gY[j] = s.frame.ng.y; gZ[j] = s.frame.ng.z;
    sX[j] = s.frame.ns.x; sY[j] = s.frame.ns.y; sZ[j] = s.frame.ns.z;
    kX[j] = s.bsdf.p.diffuse.kd.x; kY[j] = s.bsdf.p.diffuse.kd.y; kZ[j] = s.bsdf.p.diffuse.kd.z;
    smo[j] = s.frame.smooth != 0;
  }
  LaneFrame r;
  r.p = v3_load_lanes(pX, pY, pZ);
  r.ng = v3_load_lanes(gX, gY, gZ);
  r.ns = v3_load_lanes(sX, sY, sZ);
  r.kd = v3_load_lanes(kX, kY, kZ);
  r.smooth = v_loadu_lanes(smo) != 0u;
  return r;
}

// The frame of W hits: flat world-space hits from their triangle (vertex v0, edges e1, e2 at
// barycentrics hu, hv; unit normal n; Kd), surface_frame's operations; the lanes in `rich` from
// surface_at (lane_frame_rich).
MCL_INLINE LaneFrame lane_frame(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const Hit* hits,
                                MCL_GLOBAL const uint* hitInstances, MCL_GLOBAL const Ray* rays, uint first, vmask rich,
                                vuint pixel, vuint sample, uint bounce, vfloat3 v0, vfloat3 e1, vfloat3 e2, vfloat hu,
                                vfloat hv, vfloat3 n, vfloat3 dir, vfloat3 kd) {
  LaneFrame lf;
  lf.p = v3_add(v3_add(v0, v3_scale(e1, hu)), v3_scale(e2, hv));
  lf.ng = v_orient_facing(n, dir);
  lf.ns = lf.ng;
  lf.kd = kd;
  lf.smooth = v_not(rich | v_not(rich));  // none
  if (!v_any(rich)) return lf;
  return lane_frame_rich(sc, f, hits, hitInstances, rays, first, rich, pixel, sample, bounce, lf);
}

// The surfaces (surface_at) and offset ray origins of the lanes set in which[] (nonzero), the
// hits' of other kinds, which the stages shade lane by lane through their scalar functions.
MCL_INLINE void lane_surfaces(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const Hit* hits,
                              MCL_GLOBAL const uint* hitInstances, MCL_GLOBAL const Ray* rays, uint first,
                              const uint* which, vuint pixel, vuint sample, uint bounce, Surface* surfs,
                              float3* origins) {
  uint px[MCL_LANES] MCL_LANE_ALIGN, sm[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(pixel, px);
  v_store_lanes(sample, sm);
  for (uint j = 0; j < MCL_LANES; ++j) {
    if (!which[j]) continue;
    surfs[j] = surface_at(sc, f, hits[first + j], hit_instance(f, hitInstances, first + j), xyz(rays[first + j].dir),
                          sample_ref(px[j], sm[j], bounce));
    origins[j] = offset_ray_origin(surfs[j].frame.p, surfs[j].frame.ng, f->offsetScale);
  }
}

// pdf_cosine_hemisphere (sampling.h) per lane.
MCL_INLINE vfloat v_pdf_cosine_hemisphere(vfloat c) { return fmax(c, v_f(0.0f)) * MCL_INV_PI; }

// diffuse_eval (specProb 0): Kd cos(ns, wi) / pi, zero below ns and, where smooth, below ng.
MCL_INLINE vfloat3 v_lambert_eval(LaneFrame s, vfloat3 wi) {
  vmask above = v_not(s.smooth) | (v3_dot(s.ng, wi) > 0.0f);
  vfloat c = v3_dot(s.ns, wi);
  vmask lit = above & (c > 0.0f);
  vfloat cpi = c * MCL_INV_PI;
  return v3_make(vsel(lit, s.kd.x * cpi, v_f(0.0f)), vsel(lit, s.kd.y * cpi, v_f(0.0f)),
                 vsel(lit, s.kd.z * cpi, v_f(0.0f)));
}

// diffuse_pdf (specProb 0): the cosine lobe's pdf, where smooth folded above ng (pdf_cosine_folded).
MCL_INLINE vfloat v_lambert_pdf(LaneFrame s, vfloat3 wi) {
  vfloat flat = v_pdf_cosine_hemisphere(v3_dot(s.ns, wi));
  if (!v_any(s.smooth)) return flat;
  vfloat d = v3_dot(wi, s.ng);
  vfloat3 mirror = v3_sub(wi, v3_scale(s.ng, 2.0f * d));
  vfloat folded = v_pdf_cosine_hemisphere(v3_dot(s.ns, wi)) + v_pdf_cosine_hemisphere(v3_dot(s.ns, mirror));
  folded = vsel(v3_dot(s.ng, wi) > 0.0f, folded, v_f(0.0f));
  return vsel(s.smooth, folded, flat);
}

// diffuse_sample (specProb 0) from u1, u2: the direction (folded above ng where smooth), its pdf
// and weight f cos / pdf (Kd where flat and the pdf is positive).
MCL_INLINE vfloat3 v_lambert_sample(LaneFrame s, vfloat u1, vfloat u2, vfloat* pdf, vfloat3* weight) {
  vfloat3 dl = v_sample_cosine_hemisphere(u1, u2);
  vfloat3 w = v_to_world(dl, s.ns);
  vfloat flatPdf = v_pdf_cosine_hemisphere(dl.z);
  if (!v_any(s.smooth)) {
    *pdf = flatPdf;
    *weight = s.kd;
    return w;
  }
  vfloat d = v3_dot(w, s.ng);  // fold_above
  vfloat3 wi = v3_select(s.smooth & (d < 0.0f), v3_sub(w, v3_scale(s.ng, 2.0f * d)), w);
  vfloat p = v_lambert_pdf(s, wi);
  vfloat3 fc = v_lambert_eval(s, wi);
  vfloat inv = 1.0f / p;
  *pdf = vsel(s.smooth, p, flatPdf);
  *weight = v3_select(s.smooth, v3_make(fc.x * inv, fc.y * inv, fc.z * inv), s.kd);
  return wi;
}
