// shade_direct_hit: reads each item's BRDF ray (bounce) and its closest hit (bounceHits), the
// camera hit and materials; when the BRDF ray reached an emitter's front face, writes
// albedo * Le * w_brdf (albedo = Kd x texture; f cos / p = albedo for cosine sampling; w_brdf the
// MIS weight under mis) to the item's BRDF shadow slot, K. With shading normals, f cos / p =
// albedo frame_cosine_weight (folded lobe).
#pragma once
#include "stage_common.h"

MCL_INLINE void stage_shade_direct_hit(const shade_direct_hit_args* a, uint i) {
  if (i >= a->waveCount) return;
  MCL_CONSTANT const FrameParams* f = a->frame;
  Hit bh = a->bounceHits[i];
  if (bh.tri == MCL_NO_HIT || !(a->bounce[i].dir.w > 0.0f)) return;
  MCL_GLOBAL const Material* materials = a->materials;
  float3 wi = xyz(a->bounce[i].dir);
  MCL_GLOBAL const Triangle* lt = &a->tris[bh.tri];
  float3 le = emitted_toward(lt, materials, wi);
  if (!(le.x > 0.0f || le.y > 0.0f || le.z > 0.0f)) return;
  Hit h = a->hits[i];
  MCL_GLOBAL const Triangle* tri = &a->tris[h.tri];
  SurfaceFrame sf = surface_frame(a->tris, a->shading, h, xyz(a->rays[i].dir));
  float3 albedo = hit_albedo(make_texture_tables(a->textures, a->textureLevels, a->texels),
                             materials[triangle_material(tri)], tri, &a->shading[h.tri], h, xyz(a->rays[i].dir),
                             camera_spread_angle(f) * h.t);
  float weight = frame_cosine_weight(sf, wi);  // f cos / p over the albedo: 1 without shading normals
  if (f->directSampling == MCL_DIRECT_MIS && f->emitterCount > 0) {
    float area = triangle_area(lt);
    float cosLight = emitter_cosine(lt, materials, wi);
    float pick = emitter_pick_probability(area, xyz(materials[triangle_material(lt)].emission), f->emitterPower);
    float pdfLight = area_to_solid_angle(pick / area, bh.t * bh.t, cosLight);
    weight *= power_heuristic(1.0f, frame_pdf_cosine(sf, wi), (float)f->lightSamples, pdfLight);
  }
  a->shadowContrib[i * f->shadowSlots + f->lightSamples] = with_w(albedo * le * weight, 0.0f);
}
