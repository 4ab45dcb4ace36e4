// lane_lights.h: the light kinds in lane types for the packet stages: the lane instances of the
// functions written once for floats and lanes in shared/ (the area light with its emission
// textures and BLEND coverage, the environment, the point, spot, directional and sun lights, the
// emitter and record picks) and the light sample over every kind, picked per lane
// (v_sample_direct_light, sample_direct_light's lane form); Le and the emitter weight of W hits
// (lane_hit_emission). Reads the emitter table, the emitting triangles, their normals, attributes
// and materials, the textures, the light records and the environment's tables; writes nothing.
// Each lane does the float functions' operations in the same order (the same bits per lane).
#pragma once
#include "direct_light.h"
#include "stage_lanes.h"


// texture_fine per lane (emission_of's FINE, surface_texture.h): texture tex where on is set, some
// lane's texture elsewhere (masked by the caller).
MCL_INLINE vfloat4 lane_texture_fine(TextureTables tt, vuint tex, vmask on, vfloat u, vfloat v) {
  return v_texture_fine_of(tt, v_texture_desc(tt, lane_some(tex, on)), u, v);
}
MCL_DEFINE_EMISSION(v_, vfloat, vfloat3, vfloat4, vuint, vmask, v3, v_any, v_luminance, lane_texture_fine)

MCL_DEFINE_TRIANGLE_UVS(v_, vfloat, vuint, vmask, v_any, v_)

// Ke of W hits (lh, in the lanes set in m) at barycentrics hu, hv with their emission textures
// (area_light_eval's material_emission, before emitted_toward), and in *lum (unless null) the emitter table's
// luminance of those triangles (area_light_pdf's emitter_luminance).
MCL_INLINE vfloat3 lane_hit_emission(LightScene lights, const LaneHits* lh, vmask m, vfloat hu, vfloat hv, vfloat* lum) {
  vfloat u0, u1, u2, t0, t1, t2, tw;
  vmask has = v_triangle_uvs_of(lights.shading, lh->tri, lh->attrs, m, &u0, &u1, &u2, &t0, &t1, &t2, &tw);
  if (lum) *lum = v_emitter_luminance_of(lights.tex, lh->ke, lh->emissionTex, has, tw);
  return v_emission_of(lights.tex, lh->ke, lh->emissionTex, has, u0, u1, u2, t0, t1, t2, hu, hv);
}

// Rows of the picked emitters per lane: from a small table (the lanes pick a few emitters) one
// load per distinct index; from a table of at least MCL_EMITTER_LANE_ROWS_MIN (Sponza: 960
// emitting triangles) the lanes mostly pick different emitters, and one load per lane costs less
// than a pass per distinct index. Its own threshold, though today the guide table's value.
#define MCL_EMITTER_LANE_ROWS_MIN 16u
MCL_INLINE void v_gather4_emitters(uint count, MCL_GLOBAL const float* p, vuint idx, uint stride, vfloat* x,
                                   vfloat* y, vfloat* z, vfloat* w) {
  if (count < MCL_EMITTER_LANE_ROWS_MIN) v_gather4_few(p, idx, stride, x, y, z, w);
  else v_gather4(p, idx, stride, x, y, z, w);
}

// sample_direct_light (stages/direct_light.h) for the lanes set in m, the kind picked per lane as
// the scalar function picks it (the last kind in table order with a positive share whose share
// starts at or below u.x), every kind in lanes (the area light at the picked emitter, the records,
// the environment). The other lanes get no sample (pdf 0).
typedef struct {
  vfloat3 wi, le;
  vfloat pdf, tmax;
  vmask delta;
} VLightSample;

MCL_DEFINE_ACOS(v_, vfloat)
MCL_DEFINE_ATAN2(v_, vfloat, vuint, v_as_uint)
// The environment map's texels, one per lane (environment.h's G##load_float4).
MCL_INLINE vfloat4 v_load_float4(MCL_GLOBAL const float4* p, vuint i) {
  vfloat4 t;
  v_gather4((MCL_GLOBAL const float*)p, i, 4u, &t.x, &t.y, &t.z, &t.w);
  return t;
}
MCL_DEFINE_ENV_SAMPLE_TYPE(VEnvSample, vfloat, vfloat3)
MCL_DEFINE_ENVIRONMENT(v_, vfloat, vfloat3, vfloat4, vuint, vmask, v3, VEnvSample, v_, v_, v_any, v_cvt_u_f, v_cvt_f_u,
                       v_as_uint)
MCL_DEFINE_ENVIRONMENT_LIGHT(v_, vfloat, vfloat3, vmask, VLightSample, VEnvSample, v3)
MCL_DEFINE_DELTA_LIGHT_SAMPLE(v_, vfloat, vfloat3, vmask, v3, VLightSample)
MCL_DEFINE_POINT_LIGHT(v_, vfloat, vfloat3, vmask, v3, VLightSample)
MCL_DEFINE_SPOT_LIGHT(v_, vfloat, vfloat3, vfloat4, vmask, v3, VLightSample, v_)
MCL_DEFINE_DIRECTIONAL_LIGHT(v_, vfloat, vfloat3, vmask, v3, VLightSample)
MCL_DEFINE_SUN_LIGHT(v_, vfloat, vfloat3, vfloat4, vmask, v3, VLightSample, v_)

MCL_DEFINE_PICK_LIGHT_RECORD(v_, vfloat, vuint, vmask, v_any, v_)
MCL_DEFINE_AREA_LIGHT(v_, vfloat, vfloat3, vuint, vmask, v3, VLightSample, v_any, v_, v_as_uint)

// The record kinds' samples (point, spot, directional, sun) in the lanes set in m whose kind is
// one of them, kind and share as v_sample_direct_light picked them, u0 the rescaled u.x: taken
// into r with the kind's share times its pdf.
MCL_INLINE void v_sample_record_lights(MCL_CONSTANT const FrameParams* f, LightScene lights, vmask m, vuint kind,
                                       vfloat share, vfloat u0, vfloat3 origin, vfloat4 u, VLightSample* r) {
  MCL_GLOBAL const float* rf = (MCL_GLOBAL const float*)lights.records;
  const uint stride = (uint)(sizeof(LightRecord) / sizeof(float));
#define MCL_V_RECORD_KIND(k, FIRST, COUNT, SAMPLE)                                       \
  {                                                                                      \
    vmask on = m & (kind == (uint)MCL_LIGHT_##k);                                        \
    if (v_any(on)) {                                                                     \
      vuint at = v_pick_light_record_of(lights.records, f->FIRST, f->COUNT, u0, on);        \
      vfloat4 p, d, i, c;                                                                \
      v_gather4(rf, at, stride, &p.x, &p.y, &p.z, &p.w);                                 \
      v_gather4(rf + 4, at, stride, &d.x, &d.y, &d.z, &d.w);                             \
      v_gather4(rf + 8, at, stride, &i.x, &i.y, &i.z, &i.w);                             \
      v_gather4(rf + 12, at, stride, &c.x, &c.y, &c.z, &c.w);                            \
      vfloat3 pos = v3_make(p.x, p.y, p.z), dir = v3_make(d.x, d.y, d.z);                \
      vfloat3 inten = v3_make(i.x, i.y, i.z);                                            \
      (void)pos;                                                                         \
      (void)c;                                                                           \
      VLightSample s = SAMPLE;                                                           \
      r->wi = v3_select(on, s.wi, r->wi);                                                \
      r->le = v3_select(on, s.le, r->le);                                                \
      r->pdf = vsel(on, share * s.pdf, r->pdf);                                          \
      r->tmax = vsel(on, s.tmax, r->tmax);                                               \
      r->delta = r->delta | (on & s.delta);                                              \
    }                                                                                    \
  }
  MCL_V_RECORD_KIND(point, pointFirst, pointCount, v_point_light_at(pos, inten, d.w, origin))
  MCL_V_RECORD_KIND(spot, spotFirst, spotCount, v_spot_light_at(pos, dir, inten, d.w, c, origin))
  MCL_V_RECORD_KIND(directional, directionalFirst, directionalCount, v_directional_light_at(dir, inten, d.w))
  MCL_V_RECORD_KIND(sun, sunFirst, sunCount, v_sun_light_at(dir, inten, d.w, c, u.y, u.z))
#undef MCL_V_RECORD_KIND
}

MCL_INLINE VLightSample v_sample_direct_light(MCL_CONSTANT const FrameParams* f, LightScene lights, vmask m,
                                              vfloat3 origin, vfloat4 u) {
  vuint kind = v_u(MCL_LIGHT_KIND_COUNT);
  vfloat start = v_f(0.0f), share = v_f(0.0f);
  float before = 0.0f;
#define MCL_V_LIGHT_PICK(k)                                    \
  {                                                            \
    float p = k##_light_probability(f);                        \
    if (p > 0.0f) {                                            \
      vmask at = u.x >= before;                                \
      kind = vsel(at, v_u((uint)MCL_LIGHT_##k), kind);         \
      start = vsel(at, v_f(before), start);                    \
      share = vsel(at, v_f(p), share);                         \
    }                                                          \
    before += p;                                               \
  }
  MCL_LIGHT_KINDS(MCL_V_LIGHT_PICK)
#undef MCL_V_LIGHT_PICK
  VLightSample r;
  r.wi = v3_make(v_f(0.0f), v_f(0.0f), v_f(1.0f));
  r.le = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
  r.pdf = v_f(0.0f);
  r.tmax = v_f(INFINITY);
  r.delta = v_not(m | v_not(m));  // none
  vmask area = m & (kind == (uint)MCL_LIGHT_area);
  if (v_any(area)) {
    VLightSample es = v_area_light_at(f, lights, v_pick_emitter(lights.emitters, f->emitterCount, (u.x - start) / share),
                                      u.y, u.z, origin);
    r.wi = v3_select(area, es.wi, r.wi);
    r.le = v3_select(area, es.le, r.le);
    r.pdf = vsel(area, share * es.pdf, r.pdf);
    r.tmax = vsel(area, es.tmax, r.tmax);
  }
  vmask records = m & ((kind == (uint)MCL_LIGHT_point) | (kind == (uint)MCL_LIGHT_spot) |
                        (kind == (uint)MCL_LIGHT_directional) | (kind == (uint)MCL_LIGHT_sun));
  if (v_any(records)) v_sample_record_lights(f, lights, records, kind, share, (u.x - start) / share, origin, u, &r);
  vmask sky = m & (kind == (uint)MCL_LIGHT_environment);
  if (v_any(sky)) {
    VLightSample es = v_environment_light_at(f, lights, u.y, u.z);
    r.wi = v3_select(sky, es.wi, r.wi);
    r.le = v3_select(sky, es.le, r.le);
    r.pdf = vsel(sky, share * es.pdf, r.pdf);
  }
  return r;
}
