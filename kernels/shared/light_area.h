// light_area.h: the light kind "area" (light_kinds.h): emitting triangles. Reads the emitter table
// (Emitter: picked with probability area * emitter_luminance / emitterPower: luminance(Ke), or a
// textured emitter's mean over the triangle), the triangles, their normals and areas, their
// materials' emission and emission textures (with the triangles' UVs); pure; compiled by the
// kernels and the host. Emitters emit Le = Ke (x the emission texture at the point) from their
// front face (the side of cross(e1, e2)), or from both faces when the material's emission.w is set;
// a light sample on a stochastically transparent one is weighted by its coverage.
#pragma once
#include "environment.h"
#include "light_scene.h"
#include "lights.h"
#include "surface_texture.h"

// Le = le leaving a triangle of unit normal n and material m toward the viewer moving along dir
// (0 from the back face).
MCL_INLINE float3 emitted_toward(float3 n, MCL_GLOBAL const Material* m, float3 le, float3 dir) {
  bool front = dot(n, dir) < 0.0f;
  return front || m->emission.w != 0.0f ? le : make_float3(0.0f, 0.0f, 0.0f);
}


// The emitters' share of the lights' power (all samples without other lights).
MCL_INLINE float area_light_probability(MCL_CONSTANT const FrameParams* f) {
  return f->emitterCount > 0u ? f->shareArea : 0.0f;
}

// A light sample at emitter em (the emitter table's row), a uniform point on its triangle (u1, u2),
// seen from origin; pdf per solid angle within the kind (the emitter's pick included); no sample
// (no_light_sample's fields) where the emitter faces away or the point is the origin. Textured and
// stochastically transparent emitters (FrameParams::emissionTextured) take their emission texture
// at the point, and a BLEND emitter sends its emission times its coverage there: the expectation
// of a ray that meets it with that probability. Written once for floats and lanes (P, F, F3, U, M,
// V, LS, ANY, G, AS_U: the prefix, float, float3, uint, int mask, f3, LightSample, any, the table
// reads' prefix (mcl_gather4...) and a float's bits here; the lanes' in stages/lane_lights.h,
// whose emitter rows are read by G##gather4_emitters).
#define MCL_DEFINE_AREA_LIGHT(P, F, F3, U, M, V, LS, ANY, G, AS_U)                                                 \
  /* Cosine at an emitter of unit normal n for a direction wi from the shading point toward it:           \
     positive when wi reaches the emitting side (either side where twoSided, Material emission.w, is set). */ \
  MCL_INLINE F P##emitter_cosine_of(F3 n, F twoSided, F3 wi) {                                                    \
    F c = -V##_dot(n, wi);                                                                                        \
    return vsel(twoSided != 0.0f, fabs(c), c);                                                                    \
  }                                                                                                               \
  /* Solid-angle pdf within the kind of a point on an emitter of this area and table luminance lum, at        \
     squared distance dist2 and emitter cosine cosLight: the pick (area x lum / emitterPower, as the host's    \
     table) over the area, to solid angle. */                                                                     \
  MCL_INLINE F P##area_pdf_of(MCL_CONSTANT const FrameParams* f, F area, F lum, F dist2, F cosLight) {            \
    F pick = area * lum / f->emitterPower;                                                                        \
    return pick / area * dist2 / cosLight;                                                                        \
  }                                                                                                               \
  MCL_INLINE LS P##area_light_at(MCL_CONSTANT const FrameParams* f, LightScene ls, U em, F u1, F u2, F3 origin) {   \
    MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)ls.tris;                                                \
    MCL_GLOBAL const float* mf = (MCL_GLOBAL const float*)ls.materials;                                           \
    const uint n = f->emitterCount;                                                                               \
    F emTri, emCdf, emArea, emGuide;                                                                              \
    G##gather4_emitters(n, (MCL_GLOBAL const float*)ls.emitters, em, 4u, &emTri, &emCdf, &emArea, &emGuide);       \
    U lt = AS_U(emTri);                                                                                           \
    F v0x, v0y, v0z, v0w, e1x, e1y, e1z, e1w, e2x, e2y, e2z, e2w, nx, ny, nz, nw;                                 \
    G##gather4_emitters(n, tf, lt, 12u, &v0x, &v0y, &v0z, &v0w);                                                 \
    G##gather4_emitters(n, tf + 4, lt, 12u, &e1x, &e1y, &e1z, &e1w);                                             \
    G##gather4_emitters(n, tf + 8, lt, 12u, &e2x, &e2y, &e2z, &e2w);                                             \
    G##gather4_emitters(n, (MCL_GLOBAL const float*)ls.normals, lt, 4u, &nx, &ny, &nz, &nw);                     \
    U mat = AS_U(v0w); /* triangle_material */                                                                    \
    F kex, key, kez, kew;                                                                                         \
    G##gather4_few(mf + 4, mat, MCL_MATERIAL_FLOATS, &kex, &key, &kez, &kew); /* Ke, two-sided */                 \
    const F3 ke = V##_make(kex, key, kez);                                                                        \
    F su = sqrt(u1); /* sample_triangle, and its barycentrics for the emission texture */                        \
    F bu = su * (1.0f - u2), bv = su * u2;                                                                        \
    F3 p = V##_add(V##_add(V##_make(v0x, v0y, v0z), V##_scale(V##_make(e1x, e1y, e1z), bu)),                      \
                   V##_scale(V##_make(e2x, e2y, e2z), bv));                                                       \
    F3 le = ke;                                                                                                   \
    F lum = P##luminance(ke); /* emitter_luminance */                                                             \
    if (f->emissionTextured) {                                                                                    \
      F kax, kay, kaz, kaw, kmx, kmy, kmz, kmw, tu0, tu1, tu2, tv0, tv1, tv2, tw;                                \
      G##gather4_few(mf + 12, mat, MCL_MATERIAL_FLOATS, &kax, &kay, &kaz, &kaw); /* alpha */                      \
      G##gather4_few(mf + 24, mat, MCL_MATERIAL_FLOATS, &kmx, &kmy, &kmz, &kmw); /* maps: x Ke's texture */       \
      U tex = AS_U(kmx);                                                                                          \
      M has = P##triangle_uvs_of(ls.shading, lt, AS_U(e2w), (U)(0u) == 0u, &tu0, &tu1, &tu2, &tv0, &tv1, &tv2, &tw);   \
      le = P##emission_of(ls.tex, ke, tex, has, tu0, tu1, tu2, tv0, tv1, tv2, bu, bv);                            \
      M blends = (AS_U(kay) & 0x80000000u) != 0u; /* BLEND: alpha.y's sign bit */                               \
      if (ANY(blends)) {                                                                                          \
        F u, v;                                                                                                   \
        P##uv_blend(tu0, tu1, tu2, tv0, tv1, tv2, bu, bv, &u, &v); /* surface_uv */                               \
        F c = P##coverage_of(ls.tex, kay, AS_U(kax), AS_U(kaz), vsel(has, u, (F)(0.0f)), vsel(has, v, (F)(0.0f)), \
                             blends);                                                                             \
        le = V##_select(blends, V##_scale(le, c), le);                                                            \
      }                                                                                                           \
      lum = P##emitter_luminance_of(ls.tex, ke, tex, has, tw);                                                    \
    }                                                                                                             \
    F3 toLight = V##_sub(p, origin);                                                                              \
    F dist2 = V##_dot(toLight, toLight);                                                                          \
    F dist = sqrt(dist2);                                                                                         \
    F3 wi = V##_make(toLight.x / dist, toLight.y / dist, toLight.z / dist);                                       \
    F cosLight = P##emitter_cosine_of(V##_make(nx, ny, nz), kew, wi);                                             \
    M ok = (cosLight > 0.0f) & (dist > 0.0f);                                                                     \
    LS s;                                                                                                         \
    s.wi = V##_select(ok, wi, V##_make((F)(0.0f), (F)(0.0f), (F)(1.0f)));                                         \
    s.le = V##_select(ok, le, V##_make((F)(0.0f), (F)(0.0f), (F)(0.0f)));                                         \
    s.pdf = vsel(ok, P##area_pdf_of(f, emArea, lum, dist2, cosLight), (F)(0.0f));                                 \
    s.tmax = vsel(ok, dist * (1.0f - 1e-4f), (F)(INFINITY));                                                      \
    s.delta = (M)(0);                                                                                             \
    return s;                                                                                                     \
  }
MCL_INLINE void mcl_gather4_emitters(uint n, MCL_GLOBAL const float* p, uint i, uint stride, float* x, float* y,
                                     float* z, float* w) {
  (void)n;
  mcl_gather4(p, i, stride, x, y, z, w);
}
MCL_DEFINE_AREA_LIGHT(, float, float3, uint, int, f3, LightSample, MCL_ANY1, mcl_, as_uint)

// An emitter by power (u0), a uniform point on it (u1, u2); pdf per solid angle within the kind.
MCL_INLINE LightSample area_light_sample(MCL_CONSTANT const FrameParams* f, LightScene ls, float3 origin, float u0,
                                         float u1, float u2) {
  return area_light_at(f, ls, pick_emitter(ls.emitters, f->emitterCount, u0), u1, u2, origin);
}

// Pdf within the kind of reaching triangle hit.tri along hit.wi at distance hit.t (0 without
// emitters).
MCL_INLINE float area_light_pdf(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  if (f->emitterCount == 0u) return 0.0f;
  MCL_GLOBAL const Triangle* lt = &ls.tris[hit.tri];
  MCL_GLOBAL const Material* lm = &ls.materials[triangle_material(lt)];
  float4 nA = ls.normals[hit.tri];
  return area_pdf_of(f, nA.w, emitter_luminance(ls.tex, lm, lt, &ls.shading[hit.tri]), hit.t * hit.t,
                     emitter_cosine_of(xyz(nA), lm->emission.w, hit.wi));
}

// Le the triangle hit.tri sends back along -hit.wi (0 for a non-emitter or its back face).
MCL_INLINE float3 area_light_eval(MCL_CONSTANT const FrameParams* f, LightScene ls, LightHit hit) {
  (void)f;
  MCL_GLOBAL const Triangle* lt = &ls.tris[hit.tri];
  MCL_GLOBAL const Material* lm = &ls.materials[triangle_material(lt)];
  float3 le = material_emission(ls.tex, lm, lt, &ls.shading[hit.tri], hit.u, hit.v);
  return emitted_toward(xyz(ls.normals[hit.tri]), lm, le, hit.wi);
}
