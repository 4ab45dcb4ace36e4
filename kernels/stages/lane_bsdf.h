// lane_bsdf.h: the BSDF of W hits in lane types, for the packet stages: the material kinds written
// once for floats and lanes (bsdf_conductor.h, bsdf_dielectric.h, microfacet.h, bsdf_common.h's
// Fresnel terms) instantiated for lanes, and their dispatch under masks, with the Lambertian lobe
// of stage_lanes.h. Reads the hits' material fields (LaneHits); writes nothing. At W = 1 every
// mask test is the plain `if`; each lane performs the scalar functions' operations in order.
#pragma once
#include "stage_lanes.h"
#include "direct_light.h"

MCL_DEFINE_GGX(v_, v_, vfloat, vfloat3, v3)
MCL_DEFINE_FRESNEL(v_, vfloat, vfloat3, v3)
MCL_DEFINE_BSDF_SAMPLE_TYPE(vBsdfSample, vfloat, vfloat3, vmask)
MCL_DEFINE_CONDUCTOR_TYPE(vConductorBsdf, vfloat, vfloat3, vmask)
MCL_DEFINE_CONDUCTOR(v_, vfloat, vfloat3, vmask, v3, vConductorBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_DIELECTRIC_TYPE(vDielectricBsdf, vfloat, vmask)
MCL_DEFINE_DIELECTRIC(v_, vfloat, vfloat3, vmask, v3, vDielectricBsdf, LaneFrame, vBsdfSample)
MCL_DEFINE_SHADOW_DIR_FROM(v_, vfloat, vfloat3, vmask, v3)

// The BSDFs of a packet's hits (LaneHits: lamb, conductor, dielectric say which lane is which
// kind; the parameters of the other kinds are read but never used).
typedef struct {
  vmask lamb, conductor, dielectric;
  vConductorBsdf cond;
  vDielectricBsdf diel;
} LaneBsdf;

// <kind>_from_material per lane, from the materials' params0 and params1 (LaneHits).
MCL_INLINE LaneBsdf lane_bsdf(const LaneHits* lh) {
  LaneBsdf b;
  b.lamb = lh->lamb;
  b.conductor = lh->conductor;
  b.dielectric = lh->dielectric;
  b.cond = v_conductor_make(v3_make(lh->params0.x, lh->params0.y, lh->params0.z),
                            v3_make(lh->params1.x, lh->params1.y, lh->params1.z), lh->params0.w);
  b.diel = v_dielectric_make(lh->params0.x, lh->params0.y);
  return b;
}

// The lanes whose every lobe is a delta lobe (bsdf_is_delta): no light sample there.
MCL_INLINE vmask lane_bsdf_delta(const LaneBsdf* b) {
  return (b->conductor & b->cond.smooth) | (b->dielectric & b->diel.smooth);
}

// bsdf_eval (returned) and bsdf_pdf (*pdf) of wi at each lane (0 in lanes of no kind here).
MCL_INLINE vfloat3 lane_bsdf_eval_pdf(const LaneBsdf* b, LaneFrame s, vfloat3 wo, vfloat3 wi, vfloat* pdf) {
  vfloat3 fc = v_lambert_eval(s.kd, s.ng, s.ns, s.smooth, wi);
  vfloat p = v_lambert_pdf(s.ng, s.ns, s.smooth, wi);
  if (v_any(b->conductor)) {
    fc = v3_select(b->conductor, v_conductor_eval(b->cond, s, wo, wi), fc);
    p = vsel(b->conductor, v_conductor_pdf(b->cond, s, wo, wi), p);
  }
  if (v_any(b->dielectric)) {
    vfloat dp;
    vfloat d = v_dielectric_eval_pdf(b->diel, s, wo, wi, &dp);
    fc = v3_select(b->dielectric, v3_make(d, d, d), fc);
    p = vsel(b->dielectric, dp, p);
  }
  *pdf = p;
  return fc;
}

// bsdf_sample at each lane from u (x, y: the lobe's warp, w: the lobe pick).
MCL_INLINE vBsdfSample lane_bsdf_sample(const LaneBsdf* b, LaneFrame s, vfloat3 wo, vfloat4 u) {
  vBsdfSample r;
  r.wi = v_lambert_sample(s, u.x, u.y, &r.pdf, &r.weight);
  r.flags = (vmask)(0);  // a non-delta reflection
  if (v_any(b->conductor)) {
    vBsdfSample c = v_conductor_sample(b->cond, s, wo, u.x, u.y, u.w);
    r.wi = v3_select(b->conductor, c.wi, r.wi);
    r.weight = v3_select(b->conductor, c.weight, r.weight);
    r.pdf = vsel(b->conductor, c.pdf, r.pdf);
    r.flags = vsel(b->conductor, c.flags, r.flags);
  }
  if (v_any(b->dielectric)) {
    vBsdfSample d = v_dielectric_sample(b->diel, s, wo, u.x, u.y, u.w);
    r.wi = v3_select(b->dielectric, d.wi, r.wi);
    r.weight = v3_select(b->dielectric, d.weight, r.weight);
    r.pdf = vsel(b->dielectric, d.pdf, r.pdf);
    r.flags = vsel(b->dielectric, d.flags, r.flags);
  }
  return r;
}
