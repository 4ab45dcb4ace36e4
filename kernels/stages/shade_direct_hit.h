// shade_direct_hit: reads each item's BSDF ray (bounce) and its closest hit (bounceHits), the
// camera hit, materials, the attribute buffer, textures and the environment; when the BSDF ray
// reached an emitter's front face, or escaped to the environment, writes (f cos / p) * Le * w_brdf
// (f cos / p = albedo x frame_cosine_weight for a Lambertian surface: albedo = Kd x texture, 1
// without shading normals; w_brdf the MIS weight under mis) to the item's BSDF shadow slot, K.
#pragma once
#include "direct_light.h"

MCL_INLINE void stage_shade_direct_hit(const shade_direct_hit_args* a, uint i) {
  if (i >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  Hit bh = a->bounceHits[i];
  if (!(a->bounce[i].dir.w > 0.0f)) return;
  MCL_GLOBAL const Material* materials = a->materials;
  float3 wi = xyz(a->bounce[i].dir);
  float3 le;
  bool mis = f->directSampling == MCL_DIRECT_MIS;
  float pdfLight = 0.0f;
  if (bh.tri == MCL_NO_HIT) {
    if (!env_present(f)) return;
    le = env_radiance(f, a->envMap, wi);
    if (mis) pdfLight = env_light_pdf(f, a->envMap, wi);
  } else {
    MCL_GLOBAL const Triangle* lt = &a->tris[bh.tri];
    float4 nA = a->normals[bh.tri];
    le = emitted_toward(xyz(nA), &materials[triangle_material(lt)], wi);
    if (mis) pdfLight = emitter_light_pdf(f, lt, nA, materials, wi, bh.t);
  }
  if (!(le.x > 0.0f || le.y > 0.0f || le.z > 0.0f)) return;
  Hit h = a->hits[i];
  MCL_GLOBAL const Triangle* tri = &a->tris[h.tri];
  float3 dir = xyz(a->rays[i].dir);
  float3 wo = -dir;
  SurfaceFrame sf = surface_frame(a->tris, a->normals, a->shading, h, dir);
  Bsdf bsdf = bsdf_from_material(&materials[triangle_material(tri)]);
  bsdf.kd = hit_albedo(make_texture_tables(a->textures, a->textureLevels, a->texels), f,
                       materials[triangle_material(tri)], tri, a->normals[h.tri], &a->shading[h.tri], h, dir);
  float pdfBsdf = surface_bsdf_pdf(bsdf, sf, wo, wi);
  float weight = pdfLight > 0.0f ? power_heuristic(1.0f, pdfBsdf, (float)f->lightSamples, pdfLight) : 1.0f;
  if (bsdf.specProb != 0.0f && !(pdfBsdf > 0.0f)) return;
  float3 fw = bsdf.specProb == 0.0f ? bsdf.kd * frame_cosine_weight(sf, wi)
                                    : surface_bsdf_eval(bsdf, sf, wo, wi) * (1.0f / pdfBsdf);
  a->shadowContrib[i * f->shadowSlots + f->lightSamples] = with_w(fw * le * weight, 0.0f);
}
