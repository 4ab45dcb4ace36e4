// montecl.cl: the one program holding every wavefront stage kernel, generated from the stage table
// (shared/stage_table.h): kernel <stage>(frame, the table's arguments) packs its arguments into a
// <stage>_args struct and runs the stage body (stages/<stage>.h) for work item get_global_id(0), or
// a packet stage's body for the W items of its packet from item get_global_id(0) W (-DMCL_LANES=W,
// shared/lanes.h).
// Each body checks the item against its own count, so launches may round up to whole work-groups.
#include "stages/stages.h"

// The shade-side kernels inline their whole call tree (flatten): PoCL otherwise calls the stage
// body once per work item, not inlined, and passes structs (SurfaceFrame, Bsdf) to its helpers
// through the stack, where reloading them stalls on store forwarding (Cornell box direct 128x128
// 1024 spp: shade_direct 2733 -> ~1750 ms, shade_direct_hit 536 -> 92 ms, generate halved, images
// bit-identical). The traversal kernels (intersect, intersect_shadow) keep the compiler's own
// inlining, as tuned. Not in unoptimised builds (-cl-opt-disable, Oclgrind): inlining there leaves
// llvm.experimental.noalias.scope.decl calls that Oclgrind 21.10 cannot run.
#ifdef __OPTIMIZE__
#define MCL_FLATTEN __attribute__((flatten))
#else
#define MCL_FLATTEN
#endif
#define MCL_KERNEL_ATTR_generate MCL_FLATTEN
#define MCL_KERNEL_ATTR_intersect
#define MCL_KERNEL_ATTR_shade_ao MCL_FLATTEN
#define MCL_KERNEL_ATTR_shade_direct MCL_FLATTEN
#define MCL_KERNEL_ATTR_shade_direct_hit MCL_FLATTEN
#define MCL_KERNEL_ATTR_intersect_shadow
#define MCL_KERNEL_ATTR_accumulate MCL_FLATTEN
#define MCL_KERNEL_ATTR_record_aov MCL_FLATTEN
#define MCL_KERNEL_ATTR_accumulate_aov MCL_FLATTEN
#define MCL_KERNEL_ATTR_shade_path MCL_FLATTEN
#define MCL_KERNEL_ATTR_path_gather MCL_FLATTEN
#define MCL_KERNEL_ATTR_wave_ao
#define MCL_KERNEL_ATTR_wave_direct
#define MCL_KERNEL_ATTR_wave_path

// -DMCL_SCALAR_WORK_ITEMS (host/cl/device_tuning.cpp: Intel's CPU runtime) marks every kernel
// vec_type_hint(float8): the kernels compute in float8 within a work item, so that compiler does
// not pack work items into SIMD lanes (the divergent traversals ran 2-4x slower packed, and packed
// shading broke bit-identity on the glossy conformance images). Others build without it.
#ifdef MCL_SCALAR_WORK_ITEMS
#define MCL_KERNEL_ATTRIBUTES __attribute__((vec_type_hint(float8)))
#else
#define MCL_KERNEL_ATTRIBUTES
#endif

// A work item runs wave items get_global_id(0) * MCL_LANES onwards, one per lane
// (kernels/shared/lanes.h; the fused stages: group get_global_id(0)).
#define MCL_KERNEL_PARAM(type, name) , type name
#define MCL_KERNEL_VALUE(type, name) , name
#define MCL_STAGE_KERNEL(stage)                                                                    \
  __kernel MCL_KERNEL_ATTRIBUTES MCL_KERNEL_ATTR_##stage void stage(                               \
      __constant FrameParams* frame MCL_ARGS_##stage(MCL_KERNEL_PARAM)) {                          \
    stage##_args a = {frame MCL_ARGS_##stage(MCL_KERNEL_VALUE)};                                   \
    stage_##stage(&a, (uint)get_global_id(0) * MCL_LANES);                                          \
  }
MCL_STAGES(MCL_STAGE_KERNEL)
