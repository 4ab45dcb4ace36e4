// wave_fused.h: the fused wave stages wave_ao, wave_direct and wave_path: one work item takes a
// group of a wave's items through every stage of its integrator in launch order (generate, the
// stage table's schedule MCL_SCHEDULE_<integrator>, record_aov when AOVs are on, intersect_shadow,
// accumulate and accumulate_aov, or a path bounce's path_gather), reading and writing what those stages do, plus groupCounts[g], the group's count
// of occlusion queries in its own part of the queue. Group g is W pixels' runs of C samples (W = MCL_LANES, C = 2^sampleBlockShift,
// stage_common.h): items [g W C, (g + 1) W C), which are touched pixels [g W, (g + 1) W) when the
// wave starts a block and holds at most one run per pixel (the host launches these stages only
// then, render/wavefront.cpp). Every item's operations are its stages' own, in the same order, so
// the film has the unfused launches' bits; what changes is that a group's rays, hits and slots
// stay in the work item's cache and a wave is one launch instead of six or seven.
#pragma once
#include "stage_common.h"

// A stage's argument struct filled from the fused stage's fields of the same names.
#define MCL_FUSED_FIELD(type, name) , a->name
#define MCL_FUSED_ARGS(stage) {a->frame MCL_ARGS_##stage(MCL_FUSED_FIELD)}
// The same with each field cast to the stage's type: intersect_shadow reads the queue count that
// the shade stages count into (volatile there, const here).
#define MCL_FUSED_FIELD_CAST(type, name) , (type)(a->name)
#define MCL_FUSED_ARGS_CAST(stage) {a->frame MCL_ARGS_##stage(MCL_FUSED_FIELD_CAST)}

// Runs a stage body over the W items of the packet at `first`.
#define MCL_FUSED_RUN(stage, args, first) stage_##stage(&(args), (first))

// The shading stages' bodies as out-of-line functions with their whole call tree inlined, as their
// own kernels are built (montecl.cl MCL_FLATTEN: PoCL otherwise passes their structs through the
// stack); the traversals keep the compiler's own inlining, as in their kernels.
#if defined(MCL_OPENCL) && defined(__OPTIMIZE__)
#define MCL_FUSED_FLAT __attribute__((flatten, noinline))
#else
#define MCL_FUSED_FLAT MCL_INLINE
#endif
#define MCL_FUSED_WRAP(stage)                                                               \
  MCL_FUSED_FLAT void fused_##stage(const stage##_args* a, uint first) { MCL_FUSED_RUN(stage, (*a), first); }
// The traversal keeps the compiler's own inlining.
MCL_INLINE void fused_intersect(const intersect_args* a, uint first) { stage_intersect(a, first); }
MCL_FUSED_WRAP(generate)
MCL_FUSED_WRAP(shade_ao)
MCL_FUSED_WRAP(shade_direct)
MCL_FUSED_WRAP(shade_direct_hit)
MCL_FUSED_WRAP(accumulate)
MCL_FUSED_WRAP(shade_path)
MCL_FUSED_WRAP(path_gather)
MCL_FUSED_WRAP(record_aov)

// Runs `body` (naming `at`, the packet's first item) for each of the group's `packets` packets from
// `first` below `count`. Stage by stage over the whole group, not packet by packet through every
// stage: each stage's code and tables (the BVH for a traversal) stay hot in cache for the group,
// whose own rays, hits and slots are few enough to stay there too.
#define MCL_FUSED_PACKETS(packets, count, body)              \
  for (uint p = 0; p < (packets); ++p) {                    \
    const uint at = first + p * MCL_LANES;                  \
    if (at >= (count)) break;                               \
    body;                                                   \
  }

// The group's first item, or the wave's count when group g lies past its end.
MCL_INLINE uint fused_group_first(MCL_CONSTANT const FrameParams* f, uint waveCount, uint g) {
  const ulong first = (ulong)g * ((ulong)MCL_LANES << f->sampleBlockShift);
  return first < waveCount ? (uint)first : waveCount;
}

// The group's part of the shadow queue, from item `first`'s slots on (room for its items' slots),
// and its count there, groupCounts[g], cleared: declares queueBase and localCount.
#define MCL_FUSED_GROUP_QUEUE(a, g, first)                                                   \
  MCL_GLOBAL ShadowWork* queueBase = (a)->queue + (ulong)(first) * (a)->frame->shadowSlots; \
  MCL_GLOBAL volatile uint* localCount = (a)->groupCounts + (g);                            \
  *localCount = 0u

// The group's occlusion queries (intersect_shadow over its part of the queue), their count added
// to the wave's.
#define MCL_FUSED_SHADOWS(a)                                               \
  do {                                                                     \
    intersect_shadow_args sh = MCL_FUSED_ARGS_CAST(intersect_shadow);     \
    sh.queue = queueBase;                                                  \
    sh.queueCount = (MCL_GLOBAL const uint*)localCount;                    \
    const uint queries = *localCount;                                      \
    for (uint k = 0; k < queries; k += MCL_LANES)                          \
      MCL_FUSED_RUN(intersect_shadow, sh, k);                              \
    if (queries > 0u) MCL_ATOMIC_ADD((a)->queueCount, queries);            \
  } while (0)

// One row of the stage table's schedule (MCL_SCHEDULE_<integrator>) over the group's `packets`
// packets below `count`: the stage's arguments from the fused stage's, the BSDF rays bound where
// the row reads them, the group's part of the shadow queue where the stage pushes queries.
#define MCL_FUSED_RAYS_Camera(s)
#define MCL_FUSED_RAYS_Bounce(s) \
  (s).rays = a->bounce;          \
  (s).hits = a->bounceHits;      \
  (s).hitInstances = a->bounceHitInstances;
#define MCL_FUSED_QUERIES_None(s)
#define MCL_FUSED_QUERIES_Push(s) \
  (s).queue = queueBase;          \
  (s).queueCount = localCount;
#define MCL_FUSED_STEP(stage, rays, queries)                              \
  {                                                                       \
    stage##_args s = MCL_FUSED_ARGS(stage);                               \
    MCL_FUSED_RAYS_##rays(s) MCL_FUSED_QUERIES_##queries(s)               \
    MCL_FUSED_BEFORE_##stage                                              \
    MCL_FUSED_PACKETS(packets, count, fused_##stage(&s, at));             \
  }
// What a group does before a step: a path bounce's hits sorted by material kind before they are
// shaded (sort_by_kind.h; not the camera rays of bounce 0, nor at W = 1).
#define MCL_FUSED_BEFORE_intersect
#define MCL_FUSED_BEFORE_shade_ao
#define MCL_FUSED_BEFORE_shade_direct
#define MCL_FUSED_BEFORE_shade_direct_hit
#if MCL_LANES > 1
#define MCL_FUSED_BEFORE_shade_path                                                                 \
  if (a->pathBounce > 0u)                                                                           \
    fused_sort_by_kind(a->rays, a->hits, a->pathIds, a->hitInstances, a->frame->instanceCount > 0u, \
                       a->tris, a->materials, first, min(count - first, packets * (uint)MCL_LANES));
#else
#define MCL_FUSED_BEFORE_shade_path
#endif

// When the frame records AOVs: the group's items' first-hit AOVs (record_aov.h), after the shade
// stages and before the occlusion queries, where the unfused launches record them too (radiance
// then holds the camera ray's own term only).
#define MCL_FUSED_RECORD_AOV(a, packets, count)                         \
  do {                                                                  \
    if ((a)->frame->recordAovs) {                                       \
      record_aov_args rec = MCL_FUSED_ARGS(record_aov);                 \
      MCL_FUSED_PACKETS(packets, count, fused_record_aov(&rec, at));    \
    }                                                                   \
  } while (0)

// The end of a fused AO or direct wave: the group's occlusion queries, then its W pixels' samples
// into the film (and their AOVs into the AOV sums when the frame records them).
#define MCL_FUSED_SHADOW_AND_ACCUMULATE(a, g)                   \
  do {                                                          \
    MCL_FUSED_SHADOWS(a);                                       \
    accumulate_args acc = MCL_FUSED_ARGS(accumulate);           \
    fused_accumulate(&acc, (g) * MCL_LANES);                    \
    if ((a)->frame->recordAovs) {                               \
      accumulate_aov_args accAov = MCL_FUSED_ARGS(accumulate_aov); \
      MCL_FUSED_RUN(accumulate_aov, accAov, (g) * MCL_LANES);   \
    }                                                           \
  } while (0)

MCL_INLINE void stage_wave_ao(const wave_ao_args* a, uint at0) {
  const uint g = at0 / MCL_LANES;  // the group (its work item)
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint first = fused_group_first(f, a->waveCount, g), packets = 1u << f->sampleBlockShift, count = a->waveCount;
  if (first >= count) return;
  MCL_FUSED_GROUP_QUEUE(a, g, first);
  generate_args gen = MCL_FUSED_ARGS(generate);
  MCL_FUSED_PACKETS(packets, count, fused_generate(&gen, at));
  MCL_SCHEDULE_ao(MCL_FUSED_STEP)
  MCL_FUSED_RECORD_AOV(a, packets, count);
  MCL_FUSED_SHADOW_AND_ACCUMULATE(a, g);
}

MCL_INLINE void stage_wave_direct(const wave_direct_args* a, uint at0) {
  const uint g = at0 / MCL_LANES;  // the group (its work item)
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint first = fused_group_first(f, a->waveCount, g), packets = 1u << f->sampleBlockShift, count = a->waveCount;
  if (first >= count) return;
  MCL_FUSED_GROUP_QUEUE(a, g, first);
  generate_args gen = MCL_FUSED_ARGS(generate);
  MCL_FUSED_PACKETS(packets, count, fused_generate(&gen, at));
  MCL_SCHEDULE_direct(MCL_FUSED_STEP)
  MCL_FUSED_RECORD_AOV(a, packets, count);
  MCL_FUSED_SHADOW_AND_ACCUMULATE(a, g);
}

// Path tracing fuses per bounce (the host sizes each bounce by the live paths it reads back, and
// paths end at different bounces, so accumulate stays its own launch): group g is the bounce
// queue's entries [g W P, (g + 1) W P), P = MCL_FUSED_PATH_PACKETS packets, through generate (at
// bounce 0, where the queue is the wave's items), intersect, shade_path, the group's occlusion
// queries and path_gather.
#define MCL_FUSED_PATH_PACKETS 16u
#include "sort_by_kind.h"  // its scratch arrays hold a group: MCL_FUSED_PATH_PACKETS packets

MCL_INLINE void stage_wave_path(const wave_path_args* a, uint at0) {
  const uint g = at0 / MCL_LANES;  // the group (its work item)
  const uint count = *a->rayCount, packets = MCL_FUSED_PATH_PACKETS, group = MCL_LANES * packets;
  if ((ulong)g * group >= count) return;
  const uint first = g * group;
  MCL_FUSED_GROUP_QUEUE(a, g, first);
  generate_args gen = MCL_FUSED_ARGS(generate);
  path_gather_args gather = MCL_FUSED_ARGS(path_gather);
  if (a->pathBounce == 0u) MCL_FUSED_PACKETS(packets, count, fused_generate(&gen, at));
  MCL_SCHEDULE_path(MCL_FUSED_STEP)
  if (a->pathBounce == 0u) MCL_FUSED_RECORD_AOV(a, packets, count);
  MCL_FUSED_SHADOWS(a);
  MCL_FUSED_PACKETS(packets, count, fused_path_gather(&gather, at));
}
