// traverse_wide.h: closest-hit and any-hit traversal of the 8-wide BVH (WideNode,
// Bvh::wideNodes()) with an explicit stack: the layout for CPUs (--bvh-layout wide). Reads nodes and triangles; pure, so
// the host reference traversal is this same code.
//
// Speed notes (the kernels run one scalar work item per ray on CPU OpenCL, and PoCL cannot
// vectorise across work items because traversal diverges): a node's eight child boxes are tested
// at once with float8 arithmetic inside the work item (one AVX register per row; an 8-wide tree
// visits about 35% fewer nodes than a 4-wide one); the near and far rows per axis are picked once
// per ray as row indices instead of per node. The entered children come back as a bit mask with
// their distances: none entered pops the stack, one is visited without touching the stack, two
// are ordered by one compare (the farther pushed), more are pushed and insertion-sorted so the
// nearest is on top. Closest hit keeps each pushed entry's distance and skips it on pop once a hit
// is nearer; any-hit returns at the first hit. Leaf triangles are tested four at a time. Child refs
// live in uint fields, never in float lanes. A large tree misses the caches: a visit asks for the
// entered children's memory (prefetch hints on CPUs), and each traversal is a state stepped a node
// or leaf at a time, so two rays can take turns (wide_closest_hit2, wide_any_hit2).
#pragma once
#include "geometry.h"
#include "surface_texture.h"
#include "traverse_stack.h"

#ifdef MCL_OPENCL
// t where ray_triangle's tests pass (the same comparisons, NaNs included), else INFINITY. The
// relational built-ins, not the operators: Oclgrind (21.10) got the operator form of these masks
// wrong (shadow rays at a light's distance disagreed with PoCL and the host); same code on PoCL.
MCL_INLINE float4 mcl_tri_t4(float4 det, float4 u, float4 v, float4 t, float tmax) {
  const float4 zero = (float4)(0.0f), one = (float4)(1.0f);
  int4 bad = isless(fabs(det), (float4)(1e-30f)) | isless(u, zero) | isgreater(u, one) |
             isless(v, zero) | isgreater(u + v, one);
  int4 ok = ~bad & isgreater(t, zero) & isless(t, (float4)(tmax));
  return select((float4)(INFINITY), t, ok);
}
#else
inline float mcl_tri_t1(float det, float u, float v, float t, float tmax) {
  bool bad = fabs(det) < 1e-30f || u < 0.0f || u > 1.0f || v < 0.0f || u + v > 1.0f;
  return (!bad && t > 0.0f && t < tmax) ? t : INFINITY;
}
inline float4 mcl_tri_t4(float4 det, float4 u, float4 v, float4 t, float tmax) {
  return float4(mcl_tri_t1(det.x, u.x, v.x, t.x, tmax), mcl_tri_t1(det.y, u.y, v.y, t.y, tmax),
                mcl_tri_t1(det.z, u.z, v.z, t.z, tmax), mcl_tri_t1(det.w, u.w, v.w, t.w, tmax));
}
#endif

// Per-ray constants of the eight-box slab test: origin and inverse direction (splatted on the
// device), and the WideNode::bounds row of each axis's near and far plane (the max row where the
// direction is negative, -0 included, as in ray_box).
typedef struct {
#ifdef MCL_OPENCL
  float8 ox, oy, oz;
  float8 ix, iy, iz;
#else
  float ox, oy, oz;
  float ix, iy, iz;
#endif
  uint nearX, farX, nearY, farY, nearZ, farZ;
} RayBoxCtx;

MCL_INLINE RayBoxCtx make_ray_box_ctx(float3 org, float3 dir) {
  RayBoxCtx c;
  float3 inv = safe_inverse(dir);
#ifdef MCL_OPENCL
  c.ox = (float8)(org.x);
  c.oy = (float8)(org.y);
  c.oz = (float8)(org.z);
  c.ix = (float8)(inv.x);
  c.iy = (float8)(inv.y);
  c.iz = (float8)(inv.z);
#else
  c.ox = org.x;
  c.oy = org.y;
  c.oz = org.z;
  c.ix = inv.x;
  c.iy = inv.y;
  c.iz = inv.z;
#endif
  c.nearX = inv.x < 0.0f ? 1u : 0u;
  c.farX = 1u - c.nearX;
  c.nearY = inv.y < 0.0f ? 3u : 2u;
  c.farY = 5u - c.nearY;
  c.nearZ = inv.z < 0.0f ? 5u : 4u;
  c.farZ = 9u - c.nearZ;
  return c;
}

// Entry distances of the eight children of n into dist[0..7] (the same planes, operations and
// results as ray_box per child; INFINITY for a child the ray misses or enters beyond tmax).
// Returns the mask of entered children (bit i: child i).
#ifdef MCL_OPENCL
// Lane-wise mcl_max_nan1 / mcl_min_nan1 (a NaN in the first operand yields the second).
MCL_INLINE float8 mcl_max8_nan1(float8 a, float8 b) { return select(b, a, a > b); }
MCL_INLINE float8 mcl_min8_nan1(float8 a, float8 b) { return select(b, a, a < b); }
MCL_ALWAYS_INLINE uint wide_entry(MCL_GLOBAL const WideNode* n, const RayBoxCtx* c, float tmax,
                                  float* dist) {
  float8 tnx = (vload8(0, n->bounds[c->nearX]) - c->ox) * c->ix;
  float8 tfx = (vload8(0, n->bounds[c->farX]) - c->ox) * c->ix;
  float8 tny = (vload8(0, n->bounds[c->nearY]) - c->oy) * c->iy;
  float8 tfy = (vload8(0, n->bounds[c->farY]) - c->oy) * c->iy;
  float8 tnz = (vload8(0, n->bounds[c->nearZ]) - c->oz) * c->iz;
  float8 tfz = (vload8(0, n->bounds[c->farZ]) - c->oz) * c->iz;
  float8 tmin = mcl_max8_nan1(tnx, mcl_max8_nan1(tny, mcl_max8_nan1(tnz, (float8)(0.0f))));
  float8 tmx = mcl_min8_nan1(tfx, mcl_min8_nan1(tfy, mcl_min8_nan1(tfz, (float8)(tmax))));
  int8 in = isless(tmin, tmx) | isequal(tmin, tmx);  // tmin <= tmx (false on NaN)
  vstore8(select((float8)(INFINITY), tmin, in), 0, dist);
#if defined(__AVX__) && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_movmskps256)
  return (uint)__builtin_ia32_movmskps256(as_float8(in));  // one vmovmskps on x86 with AVX
#define MCL_WIDE_MOVMSK 1
#endif
#endif
#ifndef MCL_WIDE_MOVMSK
  int8 bit = in & (int8)(1, 2, 4, 8, 16, 32, 64, 128);
  int4 b4 = bit.lo | bit.hi;
  int2 b2 = b4.lo | b4.hi;
  return (uint)(b2.x | b2.y);
#endif
}
// Index of the lowest set bit of x (x != 0).
MCL_INLINE uint mcl_ctz(uint x) { return 31u - clz(x & (0u - x)); }
#else
inline uint wide_entry(const WideNode* n, const RayBoxCtx* c, float tmax, float* dist) {
  uint bits = 0;
  for (int i = 0; i < MCL_WIDE_WIDTH; ++i) {
    float tnx = (n->bounds[c->nearX][i] - c->ox) * c->ix;
    float tfx = (n->bounds[c->farX][i] - c->ox) * c->ix;
    float tny = (n->bounds[c->nearY][i] - c->oy) * c->iy;
    float tfy = (n->bounds[c->farY][i] - c->oy) * c->iy;
    float tnz = (n->bounds[c->nearZ][i] - c->oz) * c->iz;
    float tfz = (n->bounds[c->farZ][i] - c->oz) * c->iz;
    dist[i] = slab_entry(tnx, tny, tnz, tfx, tfy, tfz, tmax);
    bits |= dist[i] != INFINITY ? 1u << i : 0u;
  }
  return bits;
}
inline uint mcl_ctz(uint x) { return static_cast<uint>(__builtin_ctz(x)); }
#endif

MCL_INLINE uint wide_leaf_first(uint ref) { return (ref & ~MCL_WIDE_LEAF) >> 4; }
MCL_INLINE uint wide_leaf_count(uint ref) { return (ref & 15u) + 1u; }

// Asks for the memory of the entered children (bits) of n: an inner child's node, a leaf's first
// triangles. A large scene's tree misses the caches (Sponza: 20 MiB); the nearest child is read at
// once, but the others wait on the stack, and their loads now overlap the work until they pop.
MCL_ALWAYS_INLINE void wide_prefetch_children(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                              MCL_GLOBAL const WideNode* n, uint bits) {
#ifdef MCL_PREFETCH_HINTS
  for (; bits != 0u; bits &= bits - 1u) {
    uint r = n->child[mcl_ctz(bits)];
    MCL_GLOBAL const char* p = (r & MCL_WIDE_LEAF) ? (MCL_GLOBAL const char*)(tris + wide_leaf_first(r))
                                                    : (MCL_GLOBAL const char*)(nodes + r);
    MCL_PREFETCH(p);
    MCL_PREFETCH(p + 64);
    MCL_PREFETCH(p + 128);
    MCL_PREFETCH(p + 192);
  }
#else
  (void)nodes, (void)tris, (void)n, (void)bits;
#endif
}

// Visits interior node ref: returns the entered child to visit next (the nearest; the lower child
// on a tie) and pushes the other entered ones with their distances, farthest deepest; returns
// MCL_WIDE_EMPTY when the ray enters no child.
MCL_ALWAYS_INLINE uint wide_visit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris, uint ref,
                                  const RayBoxCtx* c, float tmax, uint* stack, float* stackT, uint* sp) {
  MCL_GLOBAL const WideNode* n = &nodes[ref];
  float dist[MCL_WIDE_WIDTH];
  uint bits = wide_entry(n, c, tmax, dist);
  if (bits == 0u) return MCL_WIDE_EMPTY;
  wide_prefetch_children(nodes, tris, n, bits);
  uint i = mcl_ctz(bits);
  bits &= bits - 1u;
  if (bits == 0u) return n->child[i];
  uint j = mcl_ctz(bits);
  bits &= bits - 1u;
  if (bits == 0u) {
    int jFirst = dist[j] < dist[i];
    uint far = jFirst ? i : j;
    stack[*sp] = n->child[far];
    stackT[*sp] = dist[far];
    *sp += 1u;
    return n->child[jFirst ? j : i];
  }
  // Three or more: push them all in child order, then insertion-sort the run by decreasing
  // distance (stable, so on a tie the lower child ends up nearer the top) and pop the top.
  uint base = *sp, top = base;
  stack[top] = n->child[i];
  stackT[top++] = dist[i];
  stack[top] = n->child[j];
  stackT[top++] = dist[j];
  while (bits != 0u) {
    uint k = mcl_ctz(bits);
    bits &= bits - 1u;
    stack[top] = n->child[k];
    stackT[top++] = dist[k];
  }
  for (uint a = base + 1u; a < top; ++a) {
    float dk = stackT[a];
    uint rk = stack[a];
    uint b = a;
    for (; b > base && stackT[b - 1u] <= dk; --b) {
      stackT[b] = stackT[b - 1u];
      stack[b] = stack[b - 1u];
    }
    stackT[b] = dk;
    stack[b] = rk;
  }
  *sp = top - 1u;
  return stack[top - 1u];
}

// Moller-Trumbore (ray_triangle's operations in the same order, lane-wise) against triangles
// tris[first + i], i < 4, the indices clamped to last (a repeated triangle repeats its t in a later
// lane, which never wins a tie). Returns t per lane (INFINITY on a miss); u, v through the pointers.
MCL_INLINE float4 ray_triangle4(MCL_GLOBAL const Triangle* tris, uint first, uint last, float3 org,
                                float3 dir, float tmax, float4* uOut, float4* vOut) {
  uint i1 = first + 1u < last ? first + 1u : last, i2 = first + 2u < last ? first + 2u : last;
  uint i3 = first + 3u < last ? first + 3u : last;
  float4 a0 = tris[first].v0, a1 = tris[i1].v0, a2 = tris[i2].v0, a3 = tris[i3].v0;
  float4 b0 = tris[first].e1, b1 = tris[i1].e1, b2 = tris[i2].e1, b3 = tris[i3].e1;
  float4 c0 = tris[first].e2, c1 = tris[i1].e2, c2 = tris[i2].e2, c3 = tris[i3].e2;
  float4 v0x = make_float4(a0.x, a1.x, a2.x, a3.x), v0y = make_float4(a0.y, a1.y, a2.y, a3.y),
         v0z = make_float4(a0.z, a1.z, a2.z, a3.z);
  float4 e1x = make_float4(b0.x, b1.x, b2.x, b3.x), e1y = make_float4(b0.y, b1.y, b2.y, b3.y),
         e1z = make_float4(b0.z, b1.z, b2.z, b3.z);
  float4 e2x = make_float4(c0.x, c1.x, c2.x, c3.x), e2y = make_float4(c0.y, c1.y, c2.y, c3.y),
         e2z = make_float4(c0.z, c1.z, c2.z, c3.z);
  float4 px = dir.y * e2z - e2y * dir.z;  // cross(dir, e2)
  float4 py = dir.z * e2x - e2z * dir.x;
  float4 pz = dir.x * e2y - e2x * dir.y;
  float4 det = e1x * px + e1y * py + e1z * pz;
  float4 inv = 1.0f / det;
  float4 sx = org.x - v0x, sy = org.y - v0y, sz = org.z - v0z;
  float4 u = (sx * px + sy * py + sz * pz) * inv;
  float4 qx = sy * e1z - e1y * sz;  // cross(s, e1)
  float4 qy = sz * e1x - e1z * sx;
  float4 qz = sx * e1y - e1x * sy;
  float4 v = (dir.x * qx + dir.y * qy + dir.z * qz) * inv;
  float4 t = (e2x * qx + e2y * qy + e2z * qz) * inv;
  *uOut = u;
  *vOut = v;
  return mcl_tri_t4(det, u, v, t, tmax);
}

// t with the lanes whose hit (t < tmax) of the ray org + t dir fails the alpha test set to
// INFINITY (alpha not null).
MCL_INLINE float4 alpha_filter4(const AlphaScene* alpha, MCL_GLOBAL const Triangle* tris, uint first,
                                uint last, float4 t, float4 u, float4 v, float tmax, float3 org, float3 dir) {
  uint i1 = first + 1u < last ? first + 1u : last, i2 = first + 2u < last ? first + 2u : last;
  uint i3 = first + 3u < last ? first + 3u : last;
  if (t.x < tmax && !alpha_hit_exists(alpha, tris, first, u.x, v.x, org, dir)) t.x = INFINITY;
  if (t.y < tmax && !alpha_hit_exists(alpha, tris, i1, u.y, v.y, org, dir)) t.y = INFINITY;
  if (t.z < tmax && !alpha_hit_exists(alpha, tris, i2, u.z, v.z, org, dir)) t.z = INFINITY;
  if (t.w < tmax && !alpha_hit_exists(alpha, tris, i3, u.w, v.w, org, dir)) t.w = INFINITY;
  return t;
}

// Leaf ref's triangles against the ray, four at a time, updating *hit (t, canonical slot, u, v; tri
// MCL_NO_HIT and t the ray's tmax while there is none) to the first hit in hit_before's order.
// Returns 1 when it changed. Every single-ray closest hit of the wide layout takes its leaves here.
MCL_ALWAYS_INLINE int wide_leaf_closest(MCL_GLOBAL const Triangle* tris, const AlphaScene* alpha, uint ref,
                                        float3 org, float3 dir, Hit* hit) {
  uint first = wide_leaf_first(ref), last = first + wide_leaf_count(ref) - 1u;
  int changed = 0;
  for (uint b = first; b <= last; b += 4u) {
    float4 u, v;
    const float tmax = leaf_tmax(hit->t, hit->tri);
    float4 t = ray_triangle4(tris, b, last, org, dir, tmax, &u, &v);
    if (alpha) t = alpha_filter4(alpha, tris, b, last, t, u, v, tmax, org, dir);
    // The nearest lane (the lowest on an equal t); then, only when it is a hit at or before the
    // hit so far (rare), hit_before's rule among the lanes at exactly that t (a repeated last
    // triangle ties with itself) and against the hit so far.
    uint i1 = b + 1u < last ? b + 1u : last, i2 = b + 2u < last ? b + 2u : last;
    uint i3 = b + 3u < last ? b + 3u : last;
    float bt = t.x, bu = u.x, bv = v.x;
    uint bi = b;
    if (t.y < bt) { bt = t.y; bu = u.y; bv = v.y; bi = i1; }
    if (t.z < bt) { bt = t.z; bu = u.z; bv = v.z; bi = i2; }
    if (t.w < bt) { bt = t.w; bu = u.w; bv = v.w; bi = i3; }
    if (bt <= hit->t && bt != INFINITY) {
      uint bc = as_uint(tris[bi].e1.w), c;
      c = as_uint(tris[i1].e1.w);
      if (t.y == bt && c < bc) { bu = u.y; bv = v.y; bc = c; }
      c = as_uint(tris[i2].e1.w);
      if (t.z == bt && c < bc) { bu = u.z; bv = v.z; bc = c; }
      c = as_uint(tris[i3].e1.w);
      if (t.w == bt && c < bc) { bu = u.w; bv = v.w; bc = c; }
      if (hit_before(bt, bc, hit->t, hit->tri)) {
        hit->t = bt;
        hit->tri = bc;
        hit->u = bu;
        hit->v = bv;
        changed = 1;
      }
    }
  }
  return changed;
}

// One ray's closest-hit traversal (wide_closest_hit) as a state that advances one node or leaf
// per wide_closest_step, so that two rays' traversals can interleave (wide_closest_hit2).
typedef struct {
  RayBoxCtx ctx;
  float3 org, dir;
  Hit hit;
  uint ref, sp;
  uint stack[MCL_WIDE_STACK_SIZE];
  float stackT[MCL_WIDE_STACK_SIZE];  // entry distance of each stacked child
} WideClosest;

MCL_ALWAYS_INLINE void wide_closest_begin(WideClosest* s, float3 org, float3 dir, float tmax) {
  s->hit.t = tmax;
  s->hit.tri = MCL_NO_HIT;
  s->hit.u = 0.0f;
  s->hit.v = 0.0f;
  s->org = org;
  s->dir = dir;
  s->ctx = make_ray_box_ctx(org, dir);
  s->sp = 0;
  // The root is wide node 0; a non-finite ray (ray_is_finite) starts at an empty slot: a miss.
  s->ref = ray_is_finite(org, dir) ? 0u : MCL_WIDE_EMPTY;
}

// Takes s->ref (a leaf's triangles, or a node's entered children) and moves s->ref to the next
// entry to take; returns 0 when none is left.
MCL_ALWAYS_INLINE int wide_closest_step(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                        const AlphaScene* alpha, WideClosest* s) {
  uint ref = s->ref;
  if (ref == MCL_WIDE_EMPTY) {
    // An empty slot (leaf bit set) is no leaf: whatever the ray, traversal never reads
    // triangles through it (no finite ray enters its empty box; a non-finite ray starts here).
  } else if (ref & MCL_WIDE_LEAF) {
    wide_leaf_closest(tris, alpha, ref, s->org, s->dir, &s->hit);
  } else {
    uint next = wide_visit(nodes, tris, ref, &s->ctx, s->hit.t, s->stack, s->stackT, &s->sp);
    if (next != MCL_WIDE_EMPTY) {
      s->ref = next;
      return 1;
    }
  }
  return pop_entered(s->stack, s->stackT, &s->sp, s->hit.t, &s->ref);
}

MCL_INLINE Hit wide_closest_end(const WideClosest* s) {
  Hit hit = s->hit;  // tri: already the canonical slot
  if (hit.tri == MCL_NO_HIT) hit.t = INFINITY;
  return hit;
}

// Closest hit along org + t*dir for t in (0, tmax); alpha (may be null) removes the hits that
// fail their material's alpha test (surface_texture.h).
MCL_INLINE Hit wide_closest_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  WideClosest s;
  wide_closest_begin(&s, org, dir, tmax);
  while (wide_closest_step(nodes, tris, alpha, &s)) {
  }
  return wide_closest_end(&s);
}

// Two rays' closest hits (each wide_closest_hit's), their traversals interleaved a step at a
// time: a large tree's nodes miss the caches, and one ray's loads wait while the other's run.
MCL_INLINE void wide_closest_hit2(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                  const AlphaScene* alpha, float3 org0, float3 dir0, float tmax0, float3 org1,
                                  float3 dir1, float tmax1, Hit* hit0, Hit* hit1) {
  WideClosest s0, s1;
  wide_closest_begin(&s0, org0, dir0, tmax0);
  wide_closest_begin(&s1, org1, dir1, tmax1);
  int live0 = 1, live1 = 1;
  while (live0 & live1) {
    live0 = wide_closest_step(nodes, tris, alpha, &s0);
    live1 = wide_closest_step(nodes, tris, alpha, &s1);
  }
  while (live0) live0 = wide_closest_step(nodes, tris, alpha, &s0);
  while (live1) live1 = wide_closest_step(nodes, tris, alpha, &s1);
  *hit0 = wide_closest_end(&s0);
  *hit1 = wide_closest_end(&s1);
}

// One ray's any-hit traversal (wide_any_hit_from) as a state that advances one node or leaf per
// wide_any_step, so that two rays' traversals can interleave (wide_any_hit2).
typedef struct {
  RayBoxCtx ctx;
  float3 org, dir;
  float tmax;
  uint ref, sp;
  int blocked;
  uint stack[MCL_WIDE_STACK_SIZE];
  float stackT[MCL_WIDE_STACK_SIZE];  // distances, for ordering the children of one node
} WideAny;

MCL_ALWAYS_INLINE void wide_any_begin(WideAny* s, float3 org, float3 dir, float tmax, uint start) {
  s->org = org;
  s->dir = dir;
  s->tmax = tmax;
  s->ctx = make_ray_box_ctx(org, dir);
  s->sp = 0;
  s->ref = start;
  s->blocked = 0;
}

// Takes s->ref and moves s->ref to the next entry; returns 0 at the first hit (s->blocked set)
// or when no entry is left.
MCL_ALWAYS_INLINE int wide_any_step(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                    const AlphaScene* alpha, WideAny* s) {
  uint ref = s->ref;
  if (ref == MCL_WIDE_EMPTY) {
    // An empty slot, or a non-finite ray: nothing to test (as in wide_closest_step).
  } else if (ref & MCL_WIDE_LEAF) {
    uint first = wide_leaf_first(ref), last = first + wide_leaf_count(ref) - 1u;
    float tmax = s->tmax;
    for (uint b = first; b <= last; b += 4u) {
      float4 u, v;
      float4 t = ray_triangle4(tris, b, last, s->org, s->dir, tmax, &u, &v);
      if (alpha) t = alpha_filter4(alpha, tris, b, last, t, u, v, tmax, s->org, s->dir);
      if (t.x < tmax || t.y < tmax || t.z < tmax || t.w < tmax) {
        s->blocked = 1;
        return 0;
      }
    }
  } else {
    uint next = wide_visit(nodes, tris, ref, &s->ctx, s->tmax, s->stack, s->stackT, &s->sp);
    if (next != MCL_WIDE_EMPTY) {
      s->ref = next;
      return 1;
    }
  }
  if (s->sp == 0u) return 0;
  s->ref = s->stack[--s->sp];
  return 1;
}

// 1 if any triangle below node `start` intersects org + t*dir for t in (0, tmax) (and passes
// the alpha test when alpha is not null), else 0. Stops at the first hit. The packet any-hit
// (traverse_packet_any.h) hands its stragglers' subtrees to this one ray at a time.
MCL_INLINE int wide_any_hit_from(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                                 const AlphaScene* alpha, float3 org, float3 dir, float tmax, uint start) {
  WideAny s;
  wide_any_begin(&s, org, dir, tmax, start);
  while (wide_any_step(nodes, tris, alpha, &s)) {
  }
  return s.blocked;
}

// The same from the root; a non-finite ray (ray_is_finite) is never blocked.
MCL_INLINE int wide_any_hit(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                            const AlphaScene* alpha, float3 org, float3 dir, float tmax) {
  return wide_any_hit_from(nodes, tris, alpha, org, dir, tmax, ray_is_finite(org, dir) ? 0u : MCL_WIDE_EMPTY);
}

// Two rays' wide_any_hit, their traversals interleaved a step at a time (as wide_closest_hit2).
MCL_INLINE void wide_any_hit2(MCL_GLOBAL const WideNode* nodes, MCL_GLOBAL const Triangle* tris,
                              const AlphaScene* alpha, float3 org0, float3 dir0, float tmax0, float3 org1,
                              float3 dir1, float tmax1, int* blocked0, int* blocked1) {
  WideAny s0, s1;
  wide_any_begin(&s0, org0, dir0, tmax0, ray_is_finite(org0, dir0) ? 0u : MCL_WIDE_EMPTY);
  wide_any_begin(&s1, org1, dir1, tmax1, ray_is_finite(org1, dir1) ? 0u : MCL_WIDE_EMPTY);
  int live0 = 1, live1 = 1;
  while (live0 & live1) {
    live0 = wide_any_step(nodes, tris, alpha, &s0);
    live1 = wide_any_step(nodes, tris, alpha, &s1);
  }
  while (live0) live0 = wide_any_step(nodes, tris, alpha, &s0);
  while (live1) live1 = wide_any_step(nodes, tris, alpha, &s1);
  *blocked0 = s0.blocked;
  *blocked1 = s1.blocked;
}
