// montecl.cl: the one program holding every wavefront stage kernel, generated from the stage table
// (shared/stage_table.h): kernel <stage>(frame, the table's arguments) packs its arguments into a
// <stage>_args struct and runs the stage body (stages/<stage>.h) for work item get_global_id(0).
// Each body checks the item against its own count, so launches may round up to whole work-groups.
#include "stages/stages.h"

// -DMCL_SCALAR_WORK_ITEMS (host/cl/device_tuning.cpp: Intel's CPU runtime) marks every kernel
// vec_type_hint(float8): the kernels compute in float8 within a work item, so that compiler does
// not pack work items into SIMD lanes (the divergent traversals ran 2-4x slower packed, and packed
// shading broke bit-identity on the glossy conformance images). Others build without it.
#ifdef MCL_SCALAR_WORK_ITEMS
#define MCL_KERNEL_ATTRIBUTES __attribute__((vec_type_hint(float8)))
#else
#define MCL_KERNEL_ATTRIBUTES
#endif

#define MCL_KERNEL_PARAM(type, name) , type name
#define MCL_KERNEL_VALUE(type, name) , name
#define MCL_STAGE_KERNEL(stage)                                                                    \
  __kernel MCL_KERNEL_ATTRIBUTES void stage(                                                       \
      __constant FrameParams* frame MCL_ARGS_##stage(MCL_KERNEL_PARAM)) {                          \
    stage##_args a = {frame MCL_ARGS_##stage(MCL_KERNEL_VALUE)};                                   \
    stage_##stage(&a, (uint)get_global_id(0));                                                     \
  }
MCL_STAGES(MCL_STAGE_KERNEL)
