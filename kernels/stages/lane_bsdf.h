// lane_bsdf.h: the BSDF of W hits in lane types, for the packet stages: the material kinds written
// once for floats and lanes (bsdf_diffuse.h's glossy mixture; bsdf_conductor.h with
// microfacet_beckmann.h and exp_neg.h; bsdf_dielectric.h, bsdf_thin_dielectric.h,
// bsdf_metal_rough.h with sheen.h, bsdf_coated_diffuse.h, bsdf_coated_conductor.h; microfacet.h and bsdf_common.h's Fresnel terms) instantiated for lanes, and
// their dispatch under masks, with the Lambertian lobe of stage_lanes.h. Reads the hits' material
// fields (LaneHits); writes nothing. At W = 1 every mask test is the plain `if`; each lane performs
// the scalar functions' operations in order.
#pragma once
#include "stage_lanes.h"
#include "direct_light.h"

MCL_DEFINE_GGX(v_, v_, vfloat, vfloat3, vmask, v3)
MCL_DEFINE_EXP_NEG(v_, vfloat, vint, v_cvt_i_f, v_cvt_f_i, v_int_as_uint, v_as_float)
MCL_DEFINE_BECKMANN(v_, v_, vfloat, vfloat3, v3)
MCL_DEFINE_SHEEN(v_, v_, vfloat, vuint, vmask, vfloat3, v3, v_as_uint, v_as_float, v_cvt_f_u)
MCL_DEFINE_FRESNEL(v_, vfloat, vfloat3, v3)
MCL_DEFINE_BSDF_SAMPLE_TYPE(vBsdfSample, vfloat, vfloat3, vmask)
MCL_DEFINE_DIFFUSE_TYPE(vDiffuseBsdf, vfloat, vfloat3)
MCL_DEFINE_DIFFUSE_GLOSSY(v_, vfloat, vfloat3, vmask, v3, v_any, vDiffuseBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_CONDUCTOR_TYPE(vConductorBsdf, vfloat, vfloat3, vmask)
MCL_DEFINE_CONDUCTOR(v_, vfloat, vfloat3, vmask, v3, v_any, vConductorBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_TRANSMISSION_TINT(v_, vfloat, vfloat3, vmask, v3)
MCL_DEFINE_DIELECTRIC_TYPE(vDielectricBsdf, vfloat, vfloat3, vmask)
MCL_DEFINE_DIELECTRIC(v_, vfloat, vfloat3, vmask, v3, v_any, vDielectricBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_THIN_DIELECTRIC_TYPE(vThinDielectricBsdf, vfloat, vfloat3)
MCL_DEFINE_THIN_DIELECTRIC(v_, vfloat, vfloat3, vmask, v3, vThinDielectricBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_METAL_ROUGH_TYPE(vMetalRoughBsdf, vfloat, vfloat3)
MCL_DEFINE_METAL_ROUGH(v_, vfloat, vfloat3, vmask, v3, v_any, vMetalRoughBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_COATED_DIFFUSE_TYPE(vCoatedDiffuseBsdf, vfloat, vfloat3, vuint)
MCL_DEFINE_COATED_DIFFUSE(v_, vfloat, vfloat3, vmask, vuint, v3, v_any, vCoatedDiffuseBsdf, LaneFrame, vBsdfSample, vRngOut,
                          v_pcg4d, v_u32_to_unit, v_as_uint, v_cvt_f_u, v_)
MCL_DEFINE_COATED_CONDUCTOR_TYPE(vCoatedConductorBsdf, vfloat, vfloat3, vuint)
MCL_DEFINE_COATED_CONDUCTOR(v_, vfloat, vfloat3, vmask, vuint, v3, v_any, vCoatedConductorBsdf, LaneFrame, vBsdfSample,
                            vRngOut, v_pcg4d, v_u32_to_unit, v_cvt_f_u, v_)
MCL_DEFINE_SHADOW_DIR_FROM(v_, vfloat, vfloat3, vmask, v3)
MCL_DEFINE_DIFFUSE_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, v_any, vDiffuseBsdf, LaneFrame)
MCL_DEFINE_CONDUCTOR_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, vConductorBsdf, LaneFrame)
MCL_DEFINE_DIELECTRIC_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, vDielectricBsdf, LaneFrame)
MCL_DEFINE_THIN_DIELECTRIC_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, vThinDielectricBsdf, LaneFrame)
MCL_DEFINE_METAL_ROUGH_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, vMetalRoughBsdf, LaneFrame)
MCL_DEFINE_COATED_DIFFUSE_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, vCoatedDiffuseBsdf, LaneFrame)
MCL_DEFINE_COATED_CONDUCTOR_WEIGHTS(v_, vfloat, vfloat3, vmask, v3, vCoatedConductorBsdf, LaneFrame)

// The BSDFs of a packet's hits (LaneHits' masks say which lane is which kind; each kind's
// parameters are made in every lane and read only in its own).
typedef struct {
  vmask lamb, glossy, conductor, dielectric, thin, metalRough, coatedDiffuse, coatedConductor;
  vDiffuseBsdf gl;
  vConductorBsdf cond;
  vDielectricBsdf diel;
  vThinDielectricBsdf sheet;
  vMetalRoughBsdf mr;
  vCoatedDiffuseBsdf cd;
  vCoatedConductorBsdf cc;
} LaneBsdf;

// The lanes shaded in lane types (the kinds above).
MCL_INLINE vmask lane_bsdf_kinds(const LaneHits* lh) {
  return lh->lamb | lh->glossy | lh->conductor | lh->dielectric | lh->thin | lh->metalRough | lh->coatedDiffuse |
         lh->coatedConductor;
}

// <kind>_from_material per lane, from the materials' params0 and params1 (LaneHits) and the frame's
// textured albedo (the diffuse kind's kd, metal_rough's base colour, the glass's tint).
MCL_INLINE LaneBsdf lane_bsdf(const LaneHits* lh, LaneFrame s) {
  LaneBsdf b;
  b.lamb = lh->lamb;
  b.glossy = lh->glossy;
  b.gl.kd = s.kd;  // diffuse_from_material: diffuse_make's lobes, then kd the textured albedo
  b.gl.ks = v3_make(lh->specular.x, lh->specular.y, lh->specular.z);
  b.gl.alpha = fmax(lh->specAlpha, MCL_GGX_MIN_ALPHA);
  b.gl.specProb = lh->specular.w;
  b.conductor = lh->conductor;
  b.dielectric = lh->dielectric;
  b.thin = lh->thin;
  b.metalRough = lh->metalRough;
  b.coatedDiffuse = lh->coatedDiffuse;
  b.cond = v_conductor_make(v3_make(lh->params0.x, lh->params0.y, lh->params0.z),
                            v3_make(lh->params1.x, lh->params1.y, lh->params1.z), lh->params0.w);
  b.cond.factor = v3_make(lh->specular.x, lh->specular.y, lh->specular.z);  // conductor_from_material
  b.cond.beckmann = lh->params1.w > 0.5f;
  b.diel = v_dielectric_make(lh->params0.x, lh->params0.y);
  b.diel.tint = v_transmission_tint_of(lh->params0.z, s.kd);
  b.sheet.ior = lh->params0.x;
  b.sheet.tint = b.diel.tint;
  // metal_rough_from_material: the clearcoat's factor and roughness in specular.x, .y; the sheen's
  // colour in params0.z, .w and specular.z, its roughness in specular.w (LaneHits' specAlpha); the
  // colour kept to metal_rough lanes, so other kinds' fields there start no sheen maths
  b.mr = v_metal_rough_coated(v_metal_rough_make(s.kd, lh->params0.x, lh->params0.y), lh->specular.x, lh->specular.y);
  b.mr = v_metal_rough_sheened(b.mr, vsel(lh->metalRough, lh->params0.z, v_f(0.0f)), vsel(lh->metalRough, lh->params0.w, v_f(0.0f)),
                               vsel(lh->metalRough, lh->specular.z, v_f(0.0f)), lh->specAlpha);
  b.cd.base = s.kd;  // coated_diffuse_from_material
  b.cd.alpha = fmax(lh->params0.x, MCL_GGX_MIN_ALPHA);
  b.cd.eta = lh->params0.y;
  b.cd.thickness = lh->params0.z;
  // Other kinds' lanes hold other fields there: no walk (their loops must not run on them).
  b.cd.maxDepth = vsel(lh->coatedDiffuse, v_as_uint(lh->params1.x), v_u(0u));
  vuint walks = v_as_uint(lh->params1.y);
  b.cd.samples = vsel(lh->coatedDiffuse & (walks > 1u), walks, v_u(1u));
  b.coatedConductor = lh->coatedConductor;  // coated_conductor_from_material; no walk in other lanes
  b.cc = v_coated_conductor_make(v3_make(lh->params0.x, lh->params0.y, lh->params0.z),
                                 v3_make(lh->params1.x, lh->params1.y, lh->params1.z), lh->params0.w, lh->params1.w,
                                 lh->specular.x, lh->specular.y,
                                 vsel(lh->coatedConductor, v_as_uint(lh->specular.z), v_u(0u)),
                                 vsel(lh->coatedConductor, v_as_uint(lh->specAlpha), v_u(1u)));
  return b;
}

// The lanes whose every lobe is a delta lobe (bsdf_is_delta): no light sample there.
MCL_INLINE vmask lane_bsdf_delta(const LaneBsdf* b) {
  return (b->conductor & b->cond.smooth) | (b->dielectric & b->diel.smooth) | b->thin;
}

// bsdf_eval (returned) and bsdf_pdf (*pdf) of wi at each lane (0 in lanes of no kind here).
MCL_INLINE vfloat3 lane_bsdf_eval_pdf(const LaneBsdf* b, LaneFrame s, vfloat3 wo, vfloat3 wi, vfloat* pdf) {
  vfloat3 fc = v_lambert_eval(s.kd, s.ng, s.ns, s.smooth, wi);
  vfloat p = v_lambert_pdf(s.ng, s.ns, s.smooth, wi);
  if (v_any(b->glossy)) {
    fc = v3_select(b->glossy, v_glossy_eval(b->gl, s, wo, wi), fc);
    p = vsel(b->glossy, v_glossy_pdf(b->gl, s, wo, wi), p);
  }
  if (v_any(b->conductor)) {
    fc = v3_select(b->conductor, v_conductor_eval(b->cond, s, wo, wi), fc);
    p = vsel(b->conductor, v_conductor_pdf(b->cond, s, wo, wi), p);
  }
  if (v_any(b->dielectric)) {
    vfloat dp;
    fc = v3_select(b->dielectric, v_dielectric_eval_pdf(b->diel, s, wo, wi, &dp), fc);
    p = vsel(b->dielectric, dp, p);
  }
  if (v_any(b->metalRough)) {
    fc = v3_select(b->metalRough, v_metal_rough_eval(b->mr, s, wo, wi), fc);
    p = vsel(b->metalRough, v_metal_rough_pdf(b->mr, s, wo, wi), p);
  }
  if (v_any(b->coatedDiffuse)) {
    fc = v3_select(b->coatedDiffuse, v_coated_diffuse_eval(b->cd, s, wo, wi), fc);
    p = vsel(b->coatedDiffuse, v_coated_diffuse_pdf(b->cd, s, wo, wi), p);
  }
  if (v_any(b->coatedConductor)) {
    fc = v3_select(b->coatedConductor, v_coated_conductor_eval(b->cc, s, wo, wi), fc);
    p = vsel(b->coatedConductor, v_coated_conductor_pdf(b->cc, s, wo, wi), p);
  }
  if (v_any(b->thin)) {  // delta lobes only: eval and pdf 0
    fc = v3_select(b->thin, v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)), fc);
    p = vsel(b->thin, v_f(0.0f), p);
  }
  *pdf = p;
  return fc;
}

// bsdf_albedo (the albedo AOV's colour) at each lane (0 in lanes of no kind here).
MCL_INLINE vfloat3 lane_bsdf_albedo(const LaneBsdf* b) {
  vfloat3 a = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
  a = v3_select(b->lamb | b->glossy, v_diffuse_albedo(b->gl), a);
  if (v_any(b->conductor)) a = v3_select(b->conductor, v_conductor_albedo(b->cond), a);
  if (v_any(b->dielectric)) a = v3_select(b->dielectric, v_dielectric_albedo(b->diel), a);
  if (v_any(b->thin)) a = v3_select(b->thin, v_thin_dielectric_albedo(b->sheet), a);
  if (v_any(b->metalRough)) a = v3_select(b->metalRough, v_metal_rough_albedo(b->mr), a);
  if (v_any(b->coatedDiffuse)) a = v3_select(b->coatedDiffuse, v_coated_diffuse_albedo(b->cd), a);
  if (v_any(b->coatedConductor)) a = v3_select(b->coatedConductor, v_coated_conductor_albedo(b->cc), a);
  return a;
}

// bsdf_direction_weight at each lane: f cos / p of a direction wi the kind's sample drew, whose
// bsdf_pdf is pdf; *counts where it contributes (none in lanes of no kind here).
MCL_INLINE vfloat3 lane_bsdf_direction_weight(const LaneBsdf* b, LaneFrame s, vfloat3 wo, vfloat3 wi, vfloat pdf,
                                              vmask* counts) {
  vmask c;
  vfloat3 w = v_diffuse_direction_weight(b->gl, s, wo, wi, pdf, &c);  // the Lambertian and glossy lanes
  *counts = c & (b->lamb | b->glossy);
#define MCL_LANE_WEIGH(mask, fn, params)                 \
  if (v_any(b->mask)) {                                  \
    w = v3_select(b->mask, fn(b->params, s, wo, wi, pdf, &c), w); \
    *counts = *counts | (c & b->mask);                   \
  }
  MCL_LANE_WEIGH(conductor, v_conductor_direction_weight, cond)
  MCL_LANE_WEIGH(dielectric, v_dielectric_direction_weight, diel)
  MCL_LANE_WEIGH(thin, v_thin_dielectric_direction_weight, sheet)
  MCL_LANE_WEIGH(metalRough, v_metal_rough_direction_weight, mr)
  MCL_LANE_WEIGH(coatedDiffuse, v_coated_diffuse_direction_weight, cd)
  MCL_LANE_WEIGH(coatedConductor, v_coated_conductor_direction_weight, cc)
#undef MCL_LANE_WEIGH
  return w;
}

// bsdf_f (no cosine) of wi at each lane of the kinds other than the Lambertian lobe (0 in the
// Lambertian lanes, whose stages spell their Kd / pi out, and in lanes of no kind here).
MCL_INLINE vfloat3 lane_bsdf_f(const LaneBsdf* b, LaneFrame s, vfloat3 wo, vfloat3 wi) {
  vfloat3 f = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
  if (v_any(b->glossy)) f = v3_select(b->glossy, v_glossy_f(b->gl, s, wo, wi), f);
  if (v_any(b->conductor)) f = v3_select(b->conductor, v_conductor_f(b->cond, s, wo, wi), f);
  if (v_any(b->dielectric)) f = v3_select(b->dielectric, v_dielectric_f(b->diel, s, wo, wi), f);
  if (v_any(b->metalRough)) f = v3_select(b->metalRough, v_metal_rough_f(b->mr, s, wo, wi), f);
  if (v_any(b->coatedDiffuse)) f = v3_select(b->coatedDiffuse, v_coated_diffuse_f(b->cd, s, wo, wi), f);
  if (v_any(b->coatedConductor)) f = v3_select(b->coatedConductor, v_coated_conductor_f(b->cc, s, wo, wi), f);
  return f;  // thin_dielectric: delta lobes only, f = 0
}

// The shadow query of a light sample along wi (length tmax) from origin; in the lanes set in far (a
// light below the geometric surface, seen through a transmitting lobe) it leaves from the far side
// instead, as a transmitted BSDF ray does (shadow_dir_from): *from, *along, *reach.
MCL_INLINE void lane_shadow_query(LaneFrame sf, float offsetScale, vmask far, vfloat3 origin, vfloat3 wi, vfloat tmax,
                                  vfloat3* from, vfloat3* along, vfloat* reach) {
  *from = origin;
  *along = wi;
  *reach = tmax;
  if (!v_any(far)) return;
  vfloat3 o = v_offset_ray_origin(sf.p, v3_neg(sf.ng), offsetScale);
  vfloat t;
  vfloat3 d = v_shadow_dir_from(origin, o, wi, tmax, &t);
  *from = v3_select(far, o, origin);
  *along = v3_select(far, d, wi);
  *reach = vsel(far, t, tmax);
}

// r's lanes set in m take sample q's.
MCL_INLINE void lane_sample_take(vBsdfSample* r, vmask m, vBsdfSample q) {
  r->wi = v3_select(m, q.wi, r->wi);
  r->weight = v3_select(m, q.weight, r->weight);
  r->pdf = vsel(m, q.pdf, r->pdf);
  r->flags = vsel(m, q.flags, r->flags);
}

// bsdf_sample at each lane from u1, u2 (the lobe's warp) and uLobe (the lobe pick).
MCL_INLINE vBsdfSample lane_bsdf_sample(const LaneBsdf* b, LaneFrame s, vfloat3 wo, vfloat u1, vfloat u2, vfloat uLobe) {
  vBsdfSample r;
  r.wi = v_lambert_sample(s, u1, u2, &r.pdf, &r.weight);
  r.flags = (vmask)(0);  // a non-delta reflection
  if (v_any(b->glossy)) lane_sample_take(&r, b->glossy, v_glossy_sample(b->gl, s, wo, u1, u2, uLobe));
  if (v_any(b->conductor)) lane_sample_take(&r, b->conductor, v_conductor_sample(b->cond, s, wo, u1, u2, uLobe));
  if (v_any(b->dielectric)) lane_sample_take(&r, b->dielectric, v_dielectric_sample(b->diel, s, wo, u1, u2, uLobe));
  if (v_any(b->thin)) lane_sample_take(&r, b->thin, v_thin_dielectric_sample(b->sheet, s, wo, u1, u2, uLobe));
  if (v_any(b->metalRough)) lane_sample_take(&r, b->metalRough, v_metal_rough_sample(b->mr, s, wo, u1, u2, uLobe));
  if (v_any(b->coatedDiffuse))
    lane_sample_take(&r, b->coatedDiffuse, v_coated_diffuse_sample(b->cd, s, wo, u1, u2, uLobe));
  if (v_any(b->coatedConductor))
    lane_sample_take(&r, b->coatedConductor, v_coated_conductor_sample(b->cc, s, wo, u1, u2, uLobe));
  return r;
}
