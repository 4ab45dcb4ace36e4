// light_area_lanes.h: the area light kind (shared/light_area.h) per lane, for the packet stages,
// and light sampling over every kind (the area kind and the record kinds, point, spot,
// directional and sun, and the environment, in lanes; textured emission through the scalar
// sample_direct_light lane by lane): reads the emitter table, the emitting triangles, their
// normals and materials, the light records (and the environment's tables); writes nothing.
// Each function does the scalar code's float operations in the same order (the same bits per lane).
#pragma once
#include "direct_light.h"
#include "stage_lanes.h"


// texture_fine per lane (emission_of's FINE, surface_texture.h): texture tex where on is set, some
// lane's texture elsewhere (masked by the caller).
MCL_INLINE vfloat4 lane_texture_fine(TextureTables tt, vuint tex, vmask on, vfloat u, vfloat v) {
  return v_texture_fine_of(tt, v_texture_desc(tt, lane_some(tex, on)), u, v);
}
MCL_DEFINE_EMISSION(v_, vfloat, vfloat3, vfloat4, vuint, vmask, v3, v_any, v_luminance, lane_texture_fine)

// triangle_uvs per lane: the corners' UVs of triangles tri where on and their attributes attrs have
// MCL_ATTR_UV (zeros elsewhere), and the textured emitters' mean luminance (tv.w); the mask of
// those lanes.
MCL_INLINE vmask lane_triangle_uvs(MCL_GLOBAL const TriangleShading* shading, vuint tri, vuint attrs, vmask on,
                                   vfloat* u0, vfloat* u1, vfloat* u2, vfloat* t0, vfloat* t1, vfloat* t2, vfloat* tw) {
  vmask has = on & ((attrs & MCL_ATTR_UV) != 0u);
  *u0 = *u1 = *u2 = *t0 = *t1 = *t2 = *tw = v_f(0.0f);
  if (v_any(has)) {
    MCL_GLOBAL const float* sh = (MCL_GLOBAL const float*)shading;
    const uint stride = (uint)(sizeof(TriangleShading) / sizeof(float));
    vuint ts = vsel(has, tri, v_u(0u));
    vfloat x, y, z;
    v_gather4(sh, ts, stride, &x, &y, &z, u0);
    v_gather4(sh + 4, ts, stride, &x, &y, &z, u1);
    v_gather4(sh + 8, ts, stride, &x, &y, &z, u2);
    v_gather4(sh + 12, ts, stride, t0, t1, t2, tw);
    *u0 = vsel(has, *u0, v_f(0.0f)), *u1 = vsel(has, *u1, v_f(0.0f)), *u2 = vsel(has, *u2, v_f(0.0f));
    *t0 = vsel(has, *t0, v_f(0.0f)), *t1 = vsel(has, *t1, v_f(0.0f)), *t2 = vsel(has, *t2, v_f(0.0f));
    *tw = vsel(has, *tw, v_f(0.0f));
  }
  return has;
}

// Ke of W hits (lh, in the lanes set in m) at barycentrics hu, hv with their emission textures
// (area_light_eval's material_emission, before emitted_toward), and in *lum the emitter table's
// luminance of those triangles (area_light_pdf's emitter_luminance).
MCL_INLINE vfloat3 lane_hit_emission(LightScene lights, const LaneHits* lh, vmask m, vfloat hu, vfloat hv, vfloat* lum) {
  vfloat u0, u1, u2, t0, t1, t2, tw;
  vmask has = lane_triangle_uvs(lights.shading, lh->tri, lh->attrs, m, &u0, &u1, &u2, &t0, &t1, &t2, &tw);
  *lum = v_emitter_luminance_of(lights.tex, lh->ke, lh->emissionTex, has, tw);
  return v_emission_of(lights.tex, lh->ke, lh->emissionTex, has, u0, u1, u2, t0, t1, t2, hu, hv);
}

// A light sample on an emitter triangle, seen from origin (sample_direct_light's area branch
// without the kind share): Le, the unit direction, the distance, and the solid-angle pdf of the
// emitter pick and point (0 where the sample is unusable: ok false, i.e. the emitter faces away or
// the point is the origin).
typedef struct {
  vfloat3 le, wi;
  vfloat dist, pdf;
  vmask ok;
} VEmitterSample;

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

// pick: the emitter-selection number (u.x, rescaled by the caller when other kinds share it);
// u2, u3: the point on the triangle (sample_triangle).
MCL_INLINE VEmitterSample v_sample_emitter(MCL_CONSTANT const FrameParams* f, LightScene lights, vfloat pick, vfloat u2,
                                           vfloat u3, vfloat3 origin) {
  MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)lights.tris;
  MCL_GLOBAL const float* mf = (MCL_GLOBAL const float*)lights.materials;
  MCL_GLOBAL const float4* normals = lights.normals;
  vuint em = v_pick_emitter(lights.emitters, f->emitterCount, pick);
  vfloat emTri, emCdf, emArea, emPad;
  const uint n = f->emitterCount;
  v_gather4_emitters(n, (MCL_GLOBAL const float*)lights.emitters, em, 4, &emTri, &emCdf, &emArea, &emPad);
  vuint lt = v_as_uint(emTri);
  vfloat l0x, l0y, l0z, l0w, l1x, l1y, l1z, l1w, l2x, l2y, l2z, l2w, lnx, lny, lnz, lnw;
  v_gather4_emitters(n, tf, lt, 12, &l0x, &l0y, &l0z, &l0w);
  v_gather4_emitters(n, tf + 4, lt, 12, &l1x, &l1y, &l1z, &l1w);
  v_gather4_emitters(n, tf + 8, lt, 12, &l2x, &l2y, &l2z, &l2w);
  v_gather4_emitters(n, (MCL_GLOBAL const float*)normals, lt, 4, &lnx, &lny, &lnz, &lnw);
  vfloat lex, ley, lez, lew;
  v_gather4_few(mf + 4, v_as_uint(l0w), MCL_MATERIAL_FLOATS, &lex, &ley, &lez, &lew);
  VEmitterSample s;
  const vfloat3 ke = v3_make(lex, ley, lez);
  vfloat su = sqrt(u2);  // sample_triangle
  vfloat bu = su * (1.0f - u3), bv = su * u3;
  vfloat3 lp = v3_add(v3_add(v3_make(l0x, l0y, l0z), v3_scale(v3_make(l1x, l1y, l1z), bu)),
                      v3_scale(v3_make(l2x, l2y, l2z), bv));
  s.le = ke;
  vfloat lum = v_luminance(ke);  // emitter_luminance
  if (f->emissionTextured) {  // an emission texture at the point, a BLEND emitter's coverage there
    vfloat kax, kay, kaz, kaw, kmx, kmy, kmz, kmw, u0, u1, u2c, t0, t1, t2, tw;
    v_gather4_few(mf + 12, v_as_uint(l0w), MCL_MATERIAL_FLOATS, &kax, &kay, &kaz, &kaw);  // alpha
    v_gather4_few(mf + 24, v_as_uint(l0w), MCL_MATERIAL_FLOATS, &kmx, &kmy, &kmz, &kmw);  // maps: x Ke's texture
    vuint tex = v_as_uint(kmx);
    vmask has = lane_triangle_uvs(lights.shading, lt, v_as_uint(l2w), v_lane_index() < MCL_LANES, &u0, &u1, &u2c, &t0, &t1, &t2, &tw);
    s.le = v_emission_of(lights.tex, ke, tex, has, u0, u1, u2c, t0, t1, t2, bu, bv);
    vmask blends = (v_as_uint(kay) & 0x80000000u) != 0u;  // material_blends
    if (v_any(blends)) {
      vfloat u, v;
      v_uv_blend(u0, u1, u2c, t0, t1, t2, bu, bv, &u, &v);  // surface_uv
      vfloat c = v_coverage_of(lights.tex, kay, v_as_uint(kax), v_as_uint(kaz), vsel(has, u, v_f(0.0f)),
                               vsel(has, v, v_f(0.0f)), blends);
      s.le = v3_select(blends, v3_scale(s.le, c), s.le);
    }
    lum = v_emitter_luminance_of(lights.tex, ke, tex, has, tw);
  }
  vfloat3 toLight = v3_sub(lp, origin);
  vfloat dist2 = v3_dot(toLight, toLight);
  s.dist = sqrt(dist2);
  s.wi = v3_make(toLight.x / s.dist, toLight.y / s.dist, toLight.z / s.dist);
  vfloat c = -v3_dot(v3_make(lnx, lny, lnz), s.wi);  // emitter_cosine
  vfloat cosLight = vsel(lew != 0.0f, fabs(c), c);
  s.ok = (cosLight > 0.0f) & (s.dist > 0.0f);
  vfloat pickP = emArea * lum / f->emitterPower;  // emitter_pick_probability
  s.pdf = vsel(s.ok, pickP / emArea * dist2 / cosLight, v_f(0.0f));  // area_to_solid_angle
  return s;
}

// sample_direct_light (stages/direct_light.h) for the lanes set in m, the kind picked per lane as
// the scalar function picks it (the last kind in table order with a positive share whose share
// starts at or below u.x): the area kind's lanes (v_sample_emitter), the record kinds' and the
// environment's in lanes, textured emission's lane by lane through the scalar function. The
// other lanes get no sample (pdf 0).
typedef struct {
  vfloat3 wi, le;
  vfloat pdf, tmax;
  vmask delta;
} VLightSample;

MCL_DEFINE_ACOS(v_, vfloat)
MCL_DEFINE_ATAN2(v_, vfloat, vuint, v_as_uint)
// The environment's table reads, one element per lane (environment.h's G##load_float*).
MCL_INLINE vfloat v_load_float(MCL_GLOBAL const float* p, vuint i) { return v_gather_float(p, i, 1u); }
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
    VEmitterSample es = v_sample_emitter(f, lights, (u.x - start) / share, u.y, u.z, origin);
    vmask ok = area & es.ok;
    r.wi = v3_select(ok, es.wi, r.wi);
    r.le = v3_select(ok, es.le, r.le);
    r.pdf = vsel(ok, share * es.pdf, r.pdf);
    r.tmax = vsel(ok, es.dist * (1.0f - 1e-4f), r.tmax);
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
