// stage_lanes.h: what the stage bodies (kernels/stages/<stage>.h) share in lane types: the lane
// forms of stage_common.h's wave-item pixel and sample, the counter-based RNG, the warps and the
// ray-origin offset, each the scalar function's operations in the same order per lane (so a lane
// gives the scalar function's bits; see kernels/shared/lanes.h), the lane frame of W hits and the
// accumulate stages' run walk. A stage's body is stage_<stage>(a, first): wave items first ..
// first + W - 1, one per lane; the generated kernel passes first = get_global_id(0) * W
// (kernels/montecl.cl). A packet that is not whole (the last of a launch) masks its missing lanes.
#pragma once
#include "../shared/lanes.h"
#include "stage_common.h"

#ifdef MCL_OPENCL
#define MCL_ATOMIC_ADD(p, n) atomic_add((p), (n))
#else
inline uint MCL_ATOMIC_ADD(volatile uint* p, uint n) { return __atomic_fetch_add(p, n, __ATOMIC_RELAXED); }
#endif

// 1 when the packet starting at `first` does not lie wholly below count (W = 1: never).
MCL_INLINE int v_packet_partial(uint first, uint count) { return MCL_LANES > 1 && count - first < MCL_LANES; }
// 1 when the packet traversals cannot take the packet of rays at `first`: a partial packet, or a
// scene whose traversals have no packet form (a two-level BVH's instances). Cut-outs do: their
// alpha test runs per lane where a flagged triangle is hit (traverse_packet.h, v_alpha_hits).
MCL_INLINE int packet_traversal_unfit(MCL_CONSTANT const FrameParams* f, uint first, uint count) {
  return v_packet_partial(first, count) || f->instanceCount > 0u;
}

// The pixels and sample indices of wave items first .. first + W - 1 (item_pixel, item_sample):
// one 64-bit division per packet, then each lane steps on from the packet's first item.
MCL_INLINE void v_item_pixel_sample(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                                    ulong waveStart, uint first, vuint* pixel, vuint* sample) {
  const uint ac = f->activeCount, c = f->sampleBlockShift;
  const ulong g0 = waveStart + first, q0 = g0 >> c;
  const uint r0 = (uint)(q0 % ac);
  vuint t = ((uint)g0 & ((1u << c) - 1u)) + v_lane_index();  // lane's offset from run q0's start
  vuint r = r0 + (t >> c);
  vuint s = v_u((uint)(q0 / ac));
  while (v_any(r >= ac)) {  // a lane past the end of the active list wraps to the next block
    vmask m = r >= ac;
    r = vsel(m, r - ac, r);
    s = vsel(m, s + 1u, s);
  }
  *sample = (s << c) | (t & ((1u << c) - 1u));
  *pixel = c == 0u && r0 + MCL_LANES <= ac ? v_load_uints(active + r0) : v_gather_uint(active, r);
}

// The same for any wave items id (one per lane, each below 2^31): 1, or 0 when a lane's run index
// leaves 32 bits (the caller then asks item_pixel and item_sample per lane).
MCL_INLINE int v_items_pixel_sample(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                                    ulong waveStart, vuint id, vuint* pixel, vuint* sample) {
  // waveStart = (q0 ac + r0) C + o0, so waveStart + id lies in run q0 ac + r0 + (o0 + id) / C.
  const uint ac = f->activeCount, c = f->sampleBlockShift;
  const ulong q = waveStart >> c;
  const uint q0 = (uint)(q / ac), r0 = (uint)(q % ac);
  vuint t = ((uint)waveStart & ((1u << c) - 1u)) + id;
  vuint g = r0 + (t >> c);
  if (v_any(g < r0)) return 0;  // r0 + run offset wrapped
  vuint qq, rr;
  v_divmod(g, ac, &qq, &rr);
  *sample = ((q0 + qq) << c) | (t & ((1u << c) - 1u));
  *pixel = v_gather_uint(active, rr);
  return 1;
}

// The walk of the accumulate stages over a packet's touched pixels' samples in a wave, in sample
// order (any block shift, a partial packet of `lanes` lanes): lane k takes touched pixel j0 + k
// (lanes past the packet repeat its last pixel, masked) and walks its runs t = j0 + k + m ac after
// run q0 = waveStart >> shift, i.e. items [(t << shift) - o0, ((t + 1) << shift) - o0) of the wave,
// clipped, each run's items in order; the lanes step together (a lane without an item at a step is
// masked) and move to their next runs together once all have finished the current one.
typedef struct {
  vuint t, i, end;  // the lane's run, item and the run's end
  vmask live;
  uint ac, count, shift, o0;
} RunWalk;

// Starts the walk; returns the lanes' pixels.
MCL_INLINE vuint run_walk_begin(RunWalk* w, MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const uint* active,
                                ulong waveStart, uint waveCount, uint j0, uint lanes) {
  w->ac = f->activeCount;
  w->count = waveCount;
  w->shift = f->sampleBlockShift;
  w->o0 = (uint)waveStart & ((1u << w->shift) - 1u);  // the wave's first item's place in its run
  w->live = v_lane_index() < lanes;
  w->t = j0 + vsel(w->live, v_lane_index(), v_u(lanes - 1u));
  vuint r = (uint)((waveStart >> w->shift) % w->ac) + w->t;  // j < ac: at most one wrap
  w->i = vsel(w->t == 0u, v_u(0u), (w->t << w->shift) - w->o0);
  vuint e = ((w->t + 1u) << w->shift) - w->o0;
  w->end = vsel(e < waveCount, e, v_u(waveCount));
  return v_gather_uint(active, vsel(r >= w->ac, r - w->ac, r));
}

// The lanes with an item (w->i) at this step; none when the walk is over. The caller then moves
// them on: w->i = w->i + v_mask01(step).
MCL_INLINE vmask run_walk_step(RunWalk* w) {
  for (;;) {
    vmask step = w->live & (w->i < w->end);
    if (v_any(step)) return step;
    w->t = w->t + w->ac;  // every lane's run is done: the next runs
    vuint start = (w->t << w->shift) - w->o0;
    w->live = w->live & (start < w->count);
    if (!v_any(w->live)) return w->live;
    w->i = start;
    vuint e = ((w->t + 1u) << w->shift) - w->o0;
    w->end = vsel(e < w->count, e, v_u(w->count));
  }
}

// --- RNG (shared/rng.h, shared/sampler.h) ----------------------------------------------------
typedef struct {
  vfloat x, y, z, w;
} vfloat4;

typedef struct {
  vuint x, y, z, w;
} vRngOut;

// A vfloat4's lanes as four arrays, for per-lane code: float4_lanes stores them, float4_lane reads
// lane j back as a float4.
typedef struct {
  float x[MCL_LANES] MCL_LANE_ALIGN, y[MCL_LANES] MCL_LANE_ALIGN, z[MCL_LANES] MCL_LANE_ALIGN, w[MCL_LANES] MCL_LANE_ALIGN;
} Float4Lanes;
MCL_INLINE Float4Lanes float4_lanes(vfloat4 v) {
  Float4Lanes l;
  v_store_lanes(v.x, l.x);
  v_store_lanes(v.y, l.y);
  v_store_lanes(v.z, l.z);
  v_store_lanes(v.w, l.w);
  return l;
}
MCL_INLINE float4 float4_lane(const Float4Lanes* l, uint j) { return make_float4(l->x[j], l->y[j], l->z[j], l->w[j]); }

MCL_DEFINE_PCG4D(v_pcg4d, vuint, vRngOut)
MCL_DEFINE_U32_TO_UNIT(v_u32_to_unit, vuint, vfloat, v_cvt_f_u)
MCL_DEFINE_UNIT4(v_unit4, vfloat4, vRngOut, v_u32_to_unit)
MCL_DEFINE_RNG_UNIFORM4(v_rng_uniform4, vuint, vfloat4, vRngOut, v_pcg4d, v_unit4)

// --- Sobol (shared/sobol.h, shared/sampler.h) -------------------------------------------------
MCL_DEFINE_MIX32(v_mix32, vuint)
MCL_DEFINE_TRANSMISSION_PICK(v_, vfloat, vuint, vmask, vfloat3, v_mix32, v_as_uint, v_u32_to_unit)
MCL_DEFINE_REVERSE_BITS(v_reverse_bits, vuint)
MCL_DEFINE_OWEN_SCRAMBLE(v_owen_scramble, vuint, v_reverse_bits)
MCL_DEFINE_SOBOL4(v_sobol4, vuint, vRngOut, v_reverse_bits)
MCL_DEFINE_SOBOL_OWEN4_BITS(v_sobol_owen4_bits, vuint, vRngOut, v_pcg4d, v_sobol4, v_owen_scramble, v_mix32)
MCL_DEFINE_SOBOL_UNIFORM4(v_sobol_uniform4, vuint, vfloat4, vRngOut, v_sobol_owen4_bits, v_unit4)
MCL_DEFINE_SAMPLE_UNIFORM4(v_sample_uniform4, vuint, vfloat4, v_sobol_uniform4, v_rng_uniform4)

// --- trig.h, sampling.h ------------------------------------------------------------------------
MCL_DEFINE_SINCOS(v_, vfloat, vint, v_cvt_i_f)
MCL_DEFINE_WARPS(v_, v_, vfloat, vfloat3, v3)
MCL_DEFINE_CAMERA(v_, vfloat, vfloat3, v3)

// --- texture.h, surface_texture.h: a packet's texture lookups -----------------------------------
// The description of each lane's texture and the size of each lane's level (TextureDesc,
// TextureLevel, gathered; the field names of the float forms), and each lane's texel.
typedef struct {
  vuint firstLevel, levelCount, dropped;
  vfloat lodBias;
  vfloat4 uvRow0, uvRow1;
} vTextureDesc;
typedef struct {
  vuint offset, width, height, format;
} vTextureLevel;

MCL_INLINE vfloat4 v4_make(vfloat x, vfloat y, vfloat z, vfloat w) {
  vfloat4 r;
  r.x = x;
  r.y = y;
  r.z = z;
  r.w = w;
  return r;
}

MCL_INLINE vTextureDesc v_texture_desc(TextureTables tt, vuint tex) {
  MCL_GLOBAL const float* p = (MCL_GLOBAL const float*)tt.textures;
  const uint stride = (uint)(sizeof(TextureDesc) / sizeof(float));
  vTextureDesc d;
  vfloat first, count, dropped;
  v_gather4(p, tex, stride, &first, &count, &dropped, &d.lodBias);
  d.firstLevel = v_as_uint(first);
  d.levelCount = v_as_uint(count);
  d.dropped = v_as_uint(dropped);
  v_gather4(p + 4, tex, stride, &d.uvRow0.x, &d.uvRow0.y, &d.uvRow0.z, &d.uvRow0.w);
  v_gather4(p + 8, tex, stride, &d.uvRow1.x, &d.uvRow1.y, &d.uvRow1.z, &d.uvRow1.w);
  return d;
}

MCL_INLINE vTextureLevel v_texture_level(TextureTables tt, vuint level) {
  vfloat o, w, h, format;
  v_gather4((MCL_GLOBAL const float*)tt.levels, level, (uint)(sizeof(TextureLevel) / sizeof(float)), &o, &w, &h, &format);
  vTextureLevel l;
  l.offset = v_as_uint(o);
  l.width = v_as_uint(w);
  l.height = v_as_uint(h);
  l.format = v_as_uint(format);
  return l;
}

// Texel (x, y) of each lane's level: the lanes' reads issued one after another, none waiting for
// another's (a scattered packet's texels are mostly cache misses).
MCL_INLINE vfloat4 v_texel_at(TextureTables tt, vTextureLevel l, vuint x, vuint y) {
#if MCL_LANES == 1
  float4 t = texel_fetch(tt, l.format, l.offset + y * l.width + x);
  return v4_make(t.x, t.y, t.z, t.w);
#else
  uint at[MCL_LANES] MCL_LANE_ALIGN, fm[MCL_LANES] MCL_LANE_ALIGN;
  float r[MCL_LANES] MCL_LANE_ALIGN, g[MCL_LANES] MCL_LANE_ALIGN, b[MCL_LANES] MCL_LANE_ALIGN, a[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(l.offset + y * l.width + x, at);
  v_store_lanes(l.format, fm);
  for (uint k = 0; k < MCL_LANES; ++k) {
    float4 t = texel_fetch(tt, fm[k], at[k]);
    r[k] = t.x;
    g[k] = t.y;
    b[k] = t.z;
    a[k] = t.w;
  }
  return v4_make(v_loadf_lanes(r), v_loadf_lanes(g), v_loadf_lanes(b), v_loadf_lanes(a));
#endif
}

MCL_DEFINE_TEXTURE_LOOKUP(v_, vfloat, vuint, vint, vfloat4, v4_make, vsel, v_any, v_int_as_uint, v_as_int, v_cvt_i_f,
                          v_cvt_u_f, v_cvt_f_u, v_as_uint, v_as_float, vTextureDesc, v_texture_desc, vTextureLevel,
                          v_texture_level, v_texel_at)
MCL_DEFINE_SURFACE_UV(v_, vfloat)

// --- geometry.h, surface.h -------------------------------------------------------------------
MCL_DEFINE_AFFINE(v_, vfloat3, vfloat4, v3)
MCL_DEFINE_OFFSET_RAY_ORIGIN(v_, vfloat, vint, vfloat3, v3, v_cvt_i_f, v_as_float, v_as_uint, v_int_as_uint)
MCL_DEFINE_ORIENT_FACING(v_, vfloat3, v3)
MCL_DEFINE_INTERPOLATE_NORMAL(v_, vfloat, vfloat3, v3)

// Pushes the occlusion queries of the lanes set in m (push_shadow_query), with one atomic per
// packet: the packet takes count(m) consecutive queue entries and its set lanes fill them in lane
// order (the queue's order does not matter: each query names its own slot); tmax per lane.
MCL_INLINE void v_push_shadow_queries(MCL_GLOBAL ShadowWork* queue, MCL_GLOBAL volatile uint* queueCount, vmask m,
                                      vfloat3 origin, vfloat3 dir, vfloat tmax, vfloat3 c, vuint slot) {
  uint count = v_count(m);
  if (count == 0) return;
  uint at = MCL_ATOMIC_ADD(queueCount, count);
#if MCL_LANES == 1
  ShadowWork w;
  w.ray.origin = make_float4(origin.x, origin.y, origin.z, 0.0f);
  w.ray.dir = make_float4(dir.x, dir.y, dir.z, tmax);
  w.r = c.x;
  w.g = c.y;
  w.b = c.z;
  w.slot = slot;
  queue[at] = w;
#else
  uint set[MCL_LANES] MCL_LANE_ALIGN, sl[MCL_LANES] MCL_LANE_ALIGN;
  float ox[MCL_LANES] MCL_LANE_ALIGN, oy[MCL_LANES] MCL_LANE_ALIGN, oz[MCL_LANES] MCL_LANE_ALIGN, dx[MCL_LANES] MCL_LANE_ALIGN, dy[MCL_LANES] MCL_LANE_ALIGN, dz[MCL_LANES] MCL_LANE_ALIGN;
  float cr[MCL_LANES] MCL_LANE_ALIGN, cg[MCL_LANES] MCL_LANE_ALIGN, cb[MCL_LANES] MCL_LANE_ALIGN, tm[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(v_mask01(m), set);
  v_store_lanes(slot, sl);
  v_store_lanes(tmax, tm);
  v3_store_lanes(origin, ox, oy, oz);
  v3_store_lanes(dir, dx, dy, dz);
  v3_store_lanes(c, cr, cg, cb);
  for (uint k = 0; k < MCL_LANES; ++k) {
    if (!set[k]) continue;
    MCL_GLOBAL float* q = (MCL_GLOBAL float*)(queue + at);
    mcl_st4(((float4)(ox[k], oy[k], oz[k], 0.0f)), q);
    mcl_st4(((float4)(dx[k], dy[k], dz[k], tm[k])), q + 4);
    mcl_st4(((float4)(cr[k], cg[k], cb[k], as_float(sl[k]))), q + 8);
    ++at;
  }
#endif
}

// --- a packet's Lambertian hits (the diffuse kind without a glossy lobe) ------------------------
// Each lane's shading frame and albedo: from the triangle alone for flat untextured world-space
// hits, else with textures, vertex colours, shading normals, normal and bump maps and instances
// (lane_frame below). The lobe itself is shading.h's, instantiated for lanes.
MCL_DEFINE_SHADING_RULE(v_, vfloat, vfloat3, vmask, v3_dot, v3_sub, v3_scale, v3_select, v3_make, v_pdf_cosine_hemisphere)

// The shading frame of W hits (SurfaceFrame per lane) and their Lambertian albedo Kd.
typedef struct {
  vfloat3 p, ng, ns, kd;
  vmask smooth;    // set where ns came from normals or a map (shading.h's folding rule applies)
  vmask backface;  // set where the ray arrived at the triangle's back face (SurfaceFrame::backface)
} LaneFrame;

MCL_DEFINE_NORMAL_MAP(v_, vfloat, vfloat3, vfloat4, vmask, v3, v4_make, LaneFrame)
MCL_DEFINE_BUMP_NORMAL(v_, vfloat, vfloat3, vmask, v3)

// luminance, the power heuristic and the emitter pick (lights.h) per lane.
MCL_DEFINE_LIGHT_PICKS(v_, vfloat, vfloat3, vuint, vmask, v_any, v_, v_cvt_u_f, v_as_uint)

// The hit triangles of a packet (lanes not in `hit` read entry 0, masked off by the caller), their
// normals and the materials' fields the stage bodies read, and which lanes lane-type code takes:
// lamb, the diffuse kind without a glossy lobe (bsdf_make's specular probability 0, computed as
// it does); glossy, that kind with one (specular: Ks and that probability, specAlpha its alpha);
// conductor, dielectric, thin, metalRough, coatedDiffuse, coatedConductor: those kinds (mixes:
// metal_rough with a transmission factor, which picks a kind per sample: lane_frame makes the
// pick, and applies a metallic-roughness texture, whose parameters are a lookup, before it,
// hit_metal_rough and hit_transmission); tinted, the lanes whose BSDF reads the
// textured albedo (the diffuse kind, metal_rough's and coated_diffuse's base colour, glTF's glass's
// tint); and of them
// all flat, whose frame comes from the triangle alone (no shading normals, normal or bump map, nor
// an instance, and where tinted no vertex colours nor albedo texture: the others' frame comes from
// lane_frame_attributes).
typedef struct {
  vfloat3 v0, e1, e2, n, kd, ke;
  vfloat area, twoSided;  // normals[].w; Material::emission.w
  vuint tri, attrs, albedoTex;  // the triangle (0 where no hit), its MCL_ATTR_* flags, Kd's texture
  vuint metalRoughTex;          // metal_rough's metallic-roughness texture (Material::maps.y)
  vuint emissionTex;            // Ke's texture (Material::maps.x)
  vuint normalMap, bumpMap;     // one more than the maps' textures, 0: none (Material::maps.z, .w)
  vmask lamb, glossy, conductor, dielectric, thin, metalRough, coatedDiffuse, coatedConductor, tinted, flat;
  vmask mixes;   // metal_rough lanes with a transmission factor (another kind per sample)
  vmask placed;   // hits in an instance: their frame made in its object space, then placed
  vuint instance; // that instance (0 in the other lanes)
  vfloat4 params0, params1;  // Material::params0, params1 (the kinds' own parameters)
  vfloat4 specular;          // Ks and the glossy lobe's probability (diffuse_make's specProb)
  vfloat specAlpha;          // the glossy lobe's alpha as the material holds it
} LaneHits;

MCL_INLINE LaneHits lane_hits(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL const Triangle* tris,
                              MCL_GLOBAL const float4* normals, MCL_GLOBAL const Material* materials,
                              MCL_GLOBAL const uint* hitInstances, uint first, uint lanes, vmask hit, vuint tri) {
  vuint t = vsel(hit, tri, v_u(0u));
  MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)tris;
  MCL_GLOBAL const float* mf = (MCL_GLOBAL const float*)materials;
  LaneHits h;
  vfloat v0w, e1w, e2w;
  v_gather4(tf, t, 12, &h.v0.x, &h.v0.y, &h.v0.z, &v0w);
  v_gather4(tf + 4, t, 12, &h.e1.x, &h.e1.y, &h.e1.z, &e1w);
  v_gather4(tf + 8, t, 12, &h.e2.x, &h.e2.y, &h.e2.z, &e2w);
  v_gather4((MCL_GLOBAL const float*)normals, t, 4, &h.n.x, &h.n.y, &h.n.z, &h.area);
  vuint mat = v_as_uint(v0w);  // triangle_material
  vfloat kdw, ksx, ksy, ksz, ksw, kax, kay, kaz, kaw, kmx, kmy, kmz, kmw;
  v_gather4(mf, mat, MCL_MATERIAL_FLOATS, &h.kd.x, &h.kd.y, &h.kd.z, &kdw);         // albedo: Kd, texture index
  v_gather4(mf + 4, mat, MCL_MATERIAL_FLOATS, &h.ke.x, &h.ke.y, &h.ke.z, &h.twoSided);  // emission: Ke, two-sided
  v_gather4(mf + 8, mat, MCL_MATERIAL_FLOATS, &ksx, &ksy, &ksz, &ksw);              // specular: Ks, alpha
  v_gather4(mf + 12, mat, MCL_MATERIAL_FLOATS, &kax, &kay, &kaz, &kaw);  // alpha test; w: the material kind (uint bits)
  v_gather4(mf + 24, mat, MCL_MATERIAL_FLOATS, &kmx, &kmy, &kmz, &kmw);  // maps: z the normal map, w the bump map (+1)
  vfloat ls = v_luminance(v3_make(ksx, ksy, ksz)), ld = v_luminance(h.kd);
  vfloat specProb = vsel(ls > 0.0f, ls / (ls + ld), v_f(0.0f));
  vuint kind = v_as_uint(kaw);
  h.lamb = hit & (specProb == 0.0f) & (kind == (uint)MCL_MATERIAL_diffuse);
  h.glossy = hit & v_not(specProb == 0.0f) & (kind == (uint)MCL_MATERIAL_diffuse);
  h.specular = v4_make(ksx, ksy, ksz, specProb);
  h.specAlpha = ksw;
  h.conductor = hit & (kind == (uint)MCL_MATERIAL_conductor);
  h.dielectric = hit & (kind == (uint)MCL_MATERIAL_dielectric);
  h.thin = hit & (kind == (uint)MCL_MATERIAL_thin_dielectric);
  h.metalRough = hit & (kind == (uint)MCL_MATERIAL_metal_rough);
  h.coatedDiffuse = hit & (kind == (uint)MCL_MATERIAL_coated_diffuse);
  h.coatedConductor = hit & (kind == (uint)MCL_MATERIAL_coated_conductor);
  h.params0 = h.params1 = v4_make(v_f(0.0f), v_f(0.0f), v_f(0.0f), v_f(0.0f));
  h.mixes = hit & v_not(hit);  // none
  if (v_any(h.conductor | h.dielectric | h.thin | h.metalRough | h.coatedDiffuse | h.coatedConductor)) {
    v_gather4(mf + 16, mat, MCL_MATERIAL_FLOATS, &h.params0.x, &h.params0.y, &h.params0.z, &h.params0.w);
    v_gather4(mf + 20, mat, MCL_MATERIAL_FLOATS, &h.params1.x, &h.params1.y, &h.params1.z, &h.params1.w);
    h.mixes = h.metalRough & (h.params1.x > 0.0f);  // hit_transmission's mix
  }
  // (glass tinted by its albedo: transmission_tint.h's flag in params0.z)
  h.tinted = h.lamb | h.glossy | h.metalRough | h.coatedDiffuse | ((h.dielectric | h.thin) & (h.params0.z > 0.0f));
  h.tri = t;
  h.attrs = v_as_uint(e2w);
  h.albedoTex = v_as_uint(kdw);
  h.metalRoughTex = v_as_uint(kmy);
  h.emissionTex = v_as_uint(kmx);
  h.normalMap = v_as_uint(kmz);
  h.bumpMap = v_as_uint(kmw);
  h.placed = hit & v_not(hit);  // none
  h.instance = v_u(0u);
  if (f->instanceCount > 0u) {  // instanced hits: their frame made in object space
    uint inst[MCL_LANES] MCL_LANE_ALIGN;
    for (uint j = 0; j < MCL_LANES; ++j) inst[j] = j < lanes ? hit_instance(f, hitInstances, first + j) : 0u;
    h.placed = hit & (v_loadu_lanes(inst) != MCL_NO_INSTANCE);
    h.instance = vsel(h.placed, v_loadu_lanes(inst), v_u(0u));
  }
  vmask albedoVaries = ((h.attrs & MCL_ATTR_COLOR) != 0u) | (h.albedoTex != MCL_NO_TEXTURE);
  h.flat = (h.tinted | h.conductor | h.dielectric | h.thin | h.coatedConductor) & ((h.attrs & MCL_ATTR_NORMALS) == 0u) &
           v_not(h.placed) & ((h.normalMap | h.bumpMap) == 0u) & v_not(h.tinted & albedoVaries) &
           (h.metalRoughTex == MCL_NO_TEXTURE) & v_not(h.mixes & (v_as_uint(h.params1.w) != 0u));
  return h;
}

// --profile's tally (FrameParams::countLanes): a packet's hits shaded in lane types (packed: the
// lanes of the kinds the stage shades in lanes, `kinds`) and the rest (a kind without a lane
// branch: lane_bsdf.h), one atomic each.
MCL_INLINE void lane_tally(MCL_CONSTANT const FrameParams* f, MCL_GLOBAL volatile uint* packedLanes,
                           MCL_GLOBAL volatile uint* aloneLanes, vmask kinds, vmask hit) {
  if (!f->countLanes) return;
  vmask packed = kinds & hit;
  uint p = v_count(packed), q = v_count(hit & v_not(packed));
  if (p) MCL_ATOMIC_ADD(packedLanes, p);
  if (q) MCL_ATOMIC_ADD(aloneLanes, q);
}

// The lanes set in m become the kind `kind` (a metal_rough hit's pick: the same kind or glass) with
// params0.x, .y, .z = metallic, roughness, tinted (hit_metal_rough and hit_transmission's result).
MCL_INLINE void lane_take_pick(LaneHits* lh, vmask m, vuint kind, vfloat metallic, vfloat roughness, vfloat tinted) {
  lh->params0.x = vsel(m, metallic, lh->params0.x);
  lh->params0.y = vsel(m, roughness, lh->params0.y);
  lh->params0.z = vsel(m, tinted, lh->params0.z);
  lh->dielectric = lh->dielectric | (m & (kind == (uint)MCL_MATERIAL_dielectric));
  lh->thin = lh->thin | (m & (kind == (uint)MCL_MATERIAL_thin_dielectric));
  lh->metalRough = lh->metalRough & v_not(m & (kind != (uint)MCL_MATERIAL_metal_rough));
}

// x where on is set, some lane's x of on elsewhere (a lookup the caller masks reads a valid index).
MCL_INLINE vuint lane_some(vuint x, vmask on) {
  uint xs[MCL_LANES] MCL_LANE_ALIGN, set[MCL_LANES] MCL_LANE_ALIGN;
  v_store_lanes(x, xs);
  v_store_lanes(v_mask01(on), set);
  uint some = 0u;
  for (uint j = 0; j < MCL_LANES; ++j)
    if (set[j]) some = xs[j];
  return vsel(on, x, v_u(some));
}

// texture_fine per lane: the finest level kept of the texture whose desc is d, bilinear.
MCL_INLINE vfloat4 v_texture_fine_of(TextureTables tt, vTextureDesc d, vfloat u, vfloat v) {
  vfloat x, y;
  v_texture_uv_of(d, u, v, &x, &y);
  return v_texture_bilinear_wrap(tt, d.firstLevel, x, y, v_as_uint(d.uvRow0.w), v_as_uint(d.uvRow1.w));
}

// apply_normal_map, then apply_bump_map, for the lanes set in m (hits with UVs and a relief map;
// N the unoriented shading normal, the corners' u in u0..u2 and v in t0..t2, at barycentrics hu, hv).
MCL_INLINE LaneFrame lane_relief(TextureTables tt, const LaneHits* lh, vmask m, vfloat3 N, vfloat u0, vfloat u1,
                                 vfloat u2, vfloat t0, vfloat t1, vfloat t2, vfloat hu, vfloat hv, LaneFrame lf) {
  vfloat u, v;
  v_uv_blend(u0, u1, u2, t0, t1, t2, hu, hv, &u, &v);
  vfloat du1 = u1 - u0, dv1 = t1 - t0, du2 = u2 - u0, dv2 = t2 - t0;
  vmask nm = m & (lh->normalMap != 0u);
  if (v_any(nm)) {
    vTextureDesc d = v_texture_desc(tt, lane_some(lh->normalMap - 1u, nm));
    vfloat4 c = v_texture_fine_of(tt, d, u, v);
    vfloat3 t = v3_make(c.x, c.y, c.z);
    vfloat4 q = v_map_uv_deltas_of(d.uvRow0, d.uvRow1, du1, dv1, du2, dv2);
    vfloat3 n = v_tangent_to_world(N, lh->e1, lh->e2, q.x, q.y, q.z, q.w, t);
    vmask filed = nm & ((lh->attrs & MCL_ATTR_TANGENTS) != 0u);
    if (v_any(filed)) {  // the file's corner tangents
      MCL_GLOBAL const float* tg = (MCL_GLOBAL const float*)tt.tangents;
      vuint at = vsel(filed, lh->tri, v_u(0u)) * 3u;
      vfloat4 c0, c1, c2;
      v_gather4(tg, at, 4, &c0.x, &c0.y, &c0.z, &c0.w);
      v_gather4(tg, at + 1u, 4, &c1.x, &c1.y, &c1.z, &c1.w);
      v_gather4(tg, at + 2u, 4, &c2.x, &c2.y, &c2.z, &c2.w);
      n = v3_select(filed, v_file_tangent_to_world(N, c0, c1, c2, hu, hv, t), n);
    }
    LaneFrame mapped = v_normal_mapped_frame(lf, N, n, t);
    lf.ns = v3_select(nm, mapped.ns, lf.ns);
    lf.smooth = vsel(nm, mapped.smooth, lf.smooth);
  }
  vmask bm = m & (lh->bumpMap != 0u);
  if (v_any(bm)) {
    vTextureDesc d = v_texture_desc(tt, lane_some(lh->bumpMap - 1u, bm));
    vfloat4 g = v_texture_fine_of(tt, d, u, v);  // the gradient per unit of the map's own UVs
    vfloat4 q = v_map_uv_deltas_of(d.uvRow0, d.uvRow1, du1, dv1, du2, dv2);
    vfloat3 n = v_bump_normal(N, lh->e1, lh->e2, q.x, q.y, q.z, q.w, g.x, g.y);
    LaneFrame mapped = v_normal_mapped_frame(lf, N, n, v3_make(g.x, g.y, v_f(1.0f)));
    lf.ns = v3_select(bm, mapped.ns, lf.ns);
    lf.smooth = vsel(bm, mapped.smooth, lf.smooth);
  }
  return lf;
}

// texture_sample of texture tex at (u, v) with footprint fp in the lanes set in on; the other
// lanes read some lane's texture (masked by the caller).
MCL_INLINE vfloat4 lane_texture(TextureTables tt, vmask on, vuint tex, vfloat u, vfloat v, vfloat fp) {
  return v_texture_sample(tt, lane_some(tex, on), u, v, fp);
}

// The lanes set in m (hits on world-space triangles) of a frame whose flat part is set:
// surface_frame's shading normal, the normal and bump maps (lane_relief), for the tinted lanes
// The corner normals n0, n1, n2 blended at hu, hv in the lanes set in hasN (surface_frame): where
// the blend is a direction, lf's ns becomes it on ng's side and smooth is set. Returns the
// unoriented shading normal (unoriented_shading_normal): that blend, else N (the triangle's).
MCL_INLINE vfloat3 lane_smooth_normal(LaneFrame* lf, vmask hasN, vfloat3 n0, vfloat3 n1, vfloat3 n2, vfloat hu,
                                      vfloat hv, vfloat3 N) {
  if (!v_any(hasN)) return N;
  vfloat3 n = v_interpolate_normal(n0, n1, n2, hu, hv);
  vmask usable = hasN & (v3_dot(n, n) > 0.0f);
  lf->ns = v3_select(usable, v_orient_to(n, lf->ng), lf->ns);
  lf->smooth = lf->smooth | usable;
  return v3_select(usable, n, N);
}

// hit_albedo's vertex colour and albedo texture (trilinear, ray-cone footprint, hit_texture), and
// the metallic-roughness texture (hit_metal_rough, into lh's params0) and the transmission texture
// (hit_transmission_texture, into params1.x), in lanes, at barycentrics
// hu, hv, distance ht.
MCL_INLINE LaneFrame lane_frame_attributes(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, vmask m,
                                           LaneHits* lh, vfloat hu, vfloat hv, vfloat ht, vfloat3 dir,
                                           LaneFrame lf) {
  vmask hasN = m & ((lh->attrs & MCL_ATTR_NORMALS) != 0u), hasUV = m & ((lh->attrs & MCL_ATTR_UV) != 0u);
  vmask coloured = m & lh->tinted & ((lh->attrs & MCL_ATTR_COLOR) != 0u);
  vmask textured = m & lh->tinted & (lh->albedoTex != MCL_NO_TEXTURE);
  vfloat3 n0 = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f)), n1 = n0, n2 = n0;
  vfloat u0 = v_f(0.0f), u1 = u0, u2 = u0, t0 = u0, t1 = u0, t2 = u0, tw;
  if (v_any(hasN | hasUV)) {  // TriangleShading: corner normals, u in w; v of the corners in tv
    MCL_GLOBAL const float* sh = (MCL_GLOBAL const float*)sc.shading;
    const uint stride = (uint)(sizeof(TriangleShading) / sizeof(float));
    vuint ts = vsel(hasN | hasUV, lh->tri, v_u(0u));
    v_gather4(sh, ts, stride, &n0.x, &n0.y, &n0.z, &u0);
    v_gather4(sh + 4, ts, stride, &n1.x, &n1.y, &n1.z, &u1);
    v_gather4(sh + 8, ts, stride, &n2.x, &n2.y, &n2.z, &u2);
    v_gather4(sh + 12, ts, stride, &t0, &t1, &t2, &tw);
  }
  vfloat3 N = lane_smooth_normal(&lf, hasN, n0, n1, n2, hu, hv, lh->n);
  vmask relief = hasUV & ((lh->normalMap | lh->bumpMap) != 0u);
  if (v_any(relief)) lf = lane_relief(sc.tex, lh, relief, N, u0, u1, u2, t0, t1, t2, hu, hv, lf);
  vfloat3 kd = lf.kd;
  if (v_any(coloured)) {  // times the vertex colour interpolated at the hit
    MCL_GLOBAL const float* c = (MCL_GLOBAL const float*)sc.tex.colors;
    vuint at = vsel(coloured, lh->tri, v_u(0u)) * 3u;
    vfloat3 c0, c1, c2;
    vfloat cw;
    v_gather4(c, at, 4, &c0.x, &c0.y, &c0.z, &cw);
    v_gather4(c, at + 1u, 4, &c1.x, &c1.y, &c1.z, &cw);
    v_gather4(c, at + 2u, 4, &c2.x, &c2.y, &c2.z, &cw);
    vfloat w = 1.0f - hu - hv;
    vfloat3 blend = v3_add(v3_add(v3_scale(c0, w), v3_scale(c1, hu)), v3_scale(c2, hv));
    kd = v3_select(coloured, v3_mul(kd, blend), kd);
  }
  vmask mrTextured = m & (lh->metalRoughTex != MCL_NO_TEXTURE);
  vmask trTextured = m & lh->mixes & (v_as_uint(lh->params1.w) != 0u);  // params1.w: the texture + 1
  if (v_any(textured | mrTextured | trTextured)) {  // hit_texture: the camera's ray cone at distance ht
    vfloat u, v;
    v_uv_blend(u0, u1, u2, t0, t1, t2, hu, hv, &u, &v);
    vfloat area = vsel(hasUV, v_uv_triangle_area(u0, u1, u2, t0, t1, t2), v_f(0.0f));
    vfloat fp = v_texture_footprint(camera_spread_angle(f) * ht, area, lh->area, v3_dot(lh->n, dir));
    u = vsel(hasUV, u, v_f(0.0f));
    v = vsel(hasUV, v, v_f(0.0f));
    if (v_any(textured)) {
      vfloat4 c = lane_texture(sc.tex, textured, lh->albedoTex, u, v, fp);
      kd = v3_select(textured, v3_mul(kd, v3_make(c.x, c.y, c.z)), kd);
    }
    if (v_any(mrTextured)) {  // hit_metal_rough: B metallic, G roughness times the factors
      vfloat4 c = lane_texture(sc.tex, mrTextured, lh->metalRoughTex, u, v, fp);
      lh->params0.x = vsel(mrTextured, lh->params0.x * fmin(fmax(c.z, 0.0f), 1.0f), lh->params0.x);
      lh->params0.y = vsel(mrTextured, lh->params0.y * fmin(fmax(c.y, 0.0f), 1.0f), lh->params0.y);
    }
    if (v_any(trTextured)) {  // hit_transmission_texture: R times the transmission factor
      vfloat4 c = lane_texture(sc.tex, trTextured, v_as_uint(lh->params1.w) - 1u, u, v, fp);
      lh->params1.x = vsel(trTextured, lh->params1.x * fmin(fmax(c.x, 0.0f), 1.0f), lh->params1.x);
    }
  }
  lf.kd = kd;
  return lf;
}

// The rows of each lane's instance's affine map (Instance::worldToObject at row 0,
// objectToWorld at row 3), gathered.
MCL_INLINE void v_instance_rows(MCL_GLOBAL const Instance* instances, vuint inst, uint row, vfloat4* r0, vfloat4* r1,
                                vfloat4* r2) {
  MCL_GLOBAL const float* p = (MCL_GLOBAL const float*)instances + 4u * row;
  const uint stride = (uint)(sizeof(Instance) / sizeof(float));
  v_gather4(p, inst, stride, &r0->x, &r0->y, &r0->z, &r0->w);
  v_gather4(p + 4, inst, stride, &r1->x, &r1->y, &r1->z, &r1->w);
  v_gather4(p + 8, inst, stride, &r2->x, &r2->y, &r2->z, &r2->w);
}

// instance_frame in the lanes set in placed: the frame made in instance inst's object space
// placed in the world (w0, w1, w2: the instance's worldToObject rows).
MCL_INLINE void lane_place_frame(MCL_GLOBAL const Instance* instances, vuint inst, vmask placed, vfloat4 w0,
                                 vfloat4 w1, vfloat4 w2, LaneFrame* lf) {
  vfloat4 o0, o1, o2;
  v_instance_rows(instances, inst, 3u, &o0, &o1, &o2);
  lf->p = v3_select(placed, v_affine_point_of(o0, o1, o2, lf->p), lf->p);
  lf->ng = v3_select(placed, v_instance_normal_of(w0, w1, w2, lf->ng), lf->ng);
  lf->ns = v3_select(placed, v_instance_normal_of(w0, w1, w2, lf->ns), lf->ns);
}

// The frame of W hits (lh, at barycentrics hu, hv and distance ht along dir), the same operations
// per lane as the float functions they are written with: flat world-space hits from their triangle alone; the lanes in `rich` with
// their shading normals, relief maps and textures (lane_frame_attributes); hits in an instance
// (lh's placed lanes) made in its object space with the unit object-space direction, then placed
// (instance_frame). lh's metal_rough lanes then hold their parameters after the metallic-roughness
// texture and, where they mix in transmission, the kind this sample's hit is (hit_transmission:
// transmission_uniform, for sample `sample` of pixel `pixel` at bounce `bounce`).
MCL_INLINE LaneFrame lane_frame(SurfaceScene sc, MCL_CONSTANT const FrameParams* f, vmask rich, vuint pixel,
                                vuint sample, uint bounce, LaneHits* lh, vfloat hu, vfloat hv, vfloat ht, vfloat3 dir) {
  vmask placed = rich & lh->placed;
  vfloat4 w0, w1, w2;
  if (v_any(placed)) {  // the object-space direction
    v_instance_rows(sc.instances, lh->instance, 0u, &w0, &w1, &w2);
    dir = v3_select(placed, v3_normalize(v_affine_vector_of(w0, w1, w2, dir)), dir);
  }
  LaneFrame lf;
  lf.p = v3_add(v3_add(lh->v0, v3_scale(lh->e1, hu)), v3_scale(lh->e2, hv));
  lf.ng = v_orient_facing(lh->n, dir);
  lf.backface = v3_dot(lh->n, dir) > 0.0f;
  lf.ns = lf.ng;
  lf.kd = lh->kd;
  lf.smooth = v_not(rich | v_not(rich));  // none
  if (v_any(rich)) lf = lane_frame_attributes(sc, f, rich, lh, hu, hv, ht, dir, lf);
  if (v_any(placed)) lane_place_frame(sc.instances, lh->instance, placed, w0, w1, w2, &lf);
  if (v_any(lh->mixes)) {  // hit_transmission: the kind this sample's hit is (transmission_uniform)
    vfloat u = f->sampler == MCL_SAMPLER_SOBOL ? v_sample_uniform4(f, pixel, sample, MCL_DIM_MIX + bounce).x
                                               : v_hit_uniform_at(lh->tri, hu, hv, dir);
    vfloat metallic = lh->params0.x, roughness = lh->params0.y, tinted = lh->params0.z;
    vuint kind = v_transmission_pick(v_u((uint)MCL_MATERIAL_metal_rough), lh->params1.x, lh->params1.y,
                                     lh->params1.z, u, &metallic, &roughness, &tinted);
    lane_take_pick(lh, lh->mixes, kind, metallic, roughness, tinted);
  }
  return lf;
}

// The shading frames (surface_frame_in: no textures or maps) of W hits, `hit` the lanes with one,
// in lanes: each from its triangle (vertex v0, edges e1, e2 at barycentrics hu, hv, unit normal,
// facing dir) and its corner normals where it has them; a hit in an instance made in its object
// space with the object-space direction (not normalised, as surface_frame_in), then placed. kd is
// left 0.
MCL_INLINE LaneFrame lane_surface_frame(MCL_GLOBAL const Triangle* tris, MCL_GLOBAL const float4* normals,
                                        MCL_GLOBAL const TriangleShading* shading,
                                        MCL_GLOBAL const Instance* instances, MCL_CONSTANT const FrameParams* f,
                                        MCL_GLOBAL const uint* hitInstances, uint first, uint lanes, vmask hit,
                                        vuint tri, vfloat hu, vfloat hv, vfloat3 dir) {
  vuint t = vsel(hit, tri, v_u(0u));  // misses read triangle 0 and are masked off
  MCL_GLOBAL const float* tf = (MCL_GLOBAL const float*)tris;
  vfloat3 v0, e1, e2, n;
  vfloat v0w, e1w, e2w, area;
  v_gather4(tf, t, 12, &v0.x, &v0.y, &v0.z, &v0w);
  v_gather4(tf + 4, t, 12, &e1.x, &e1.y, &e1.z, &e1w);
  v_gather4(tf + 8, t, 12, &e2.x, &e2.y, &e2.z, &e2w);
  v_gather4((MCL_GLOBAL const float*)normals, t, 4, &n.x, &n.y, &n.z, &area);
  vmask placed = hit & v_not(hit);  // none
  vuint instance = v_u(0u);
  vfloat4 w0, w1, w2;
  if (f->instanceCount > 0u) {
    uint inst[MCL_LANES] MCL_LANE_ALIGN;
    for (uint j = 0; j < MCL_LANES; ++j) inst[j] = j < lanes ? hit_instance(f, hitInstances, first + j) : 0u;
    placed = hit & (v_loadu_lanes(inst) != MCL_NO_INSTANCE);
    instance = vsel(placed, v_loadu_lanes(inst), v_u(0u));
  }
  if (v_any(placed)) {  // the object-space direction
    v_instance_rows(instances, instance, 0u, &w0, &w1, &w2);
    dir = v3_select(placed, v_affine_vector_of(w0, w1, w2, dir), dir);
  }
  LaneFrame lf;
  lf.p = v3_add(v3_add(v0, v3_scale(e1, hu)), v3_scale(e2, hv));
  lf.ng = v_orient_facing(n, dir);
  lf.backface = v3_dot(n, dir) > 0.0f;
  lf.ns = lf.ng;
  lf.kd = v3_make(v_f(0.0f), v_f(0.0f), v_f(0.0f));
  lf.smooth = hit & v_not(hit);  // none
  vmask hasN = hit & ((v_as_uint(e2w) & MCL_ATTR_NORMALS) != 0u);
  if (v_any(hasN)) {  // TriangleShading: the corner normals
    MCL_GLOBAL const float* sh = (MCL_GLOBAL const float*)shading;
    const uint stride = (uint)(sizeof(TriangleShading) / sizeof(float));
    vuint ts = vsel(hasN, t, v_u(0u));
    vfloat3 n0, n1, n2;
    vfloat u0, u1, u2;
    v_gather4(sh, ts, stride, &n0.x, &n0.y, &n0.z, &u0);
    v_gather4(sh + 4, ts, stride, &n1.x, &n1.y, &n1.z, &u1);
    v_gather4(sh + 8, ts, stride, &n2.x, &n2.y, &n2.z, &u2);
    (void)lane_smooth_normal(&lf, hasN, n0, n1, n2, hu, hv, n);
  }
  if (v_any(placed)) lane_place_frame(instances, instance, placed, w0, w1, w2, &lf);
  return lf;
}

// frame_sample_direction (shading.h) per lane: dirLocal around ns, folded above ng where smooth.
MCL_INLINE vfloat3 lane_frame_sample_direction(LaneFrame s, vfloat3 dirLocal) {
  vfloat3 w = v_to_world(dirLocal, s.ns);
  return v_any(s.smooth) ? v3_select(s.smooth, v_fold_above(w, s.ng), w) : w;
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
  vfloat3 wi = v3_select(s.smooth, v_fold_above(w, s.ng), w);
  vfloat p = v_lambert_pdf(s.ng, s.ns, s.smooth, wi);
  vfloat3 fc = v_lambert_eval(s.kd, s.ng, s.ns, s.smooth, wi);
  vfloat inv = 1.0f / p;
  *pdf = vsel(s.smooth, p, flatPdf);
  *weight = v3_select(s.smooth, v3_make(fc.x * inv, fc.y * inv, fc.z * inv), s.kd);
  return wi;
}
