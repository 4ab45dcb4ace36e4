// montecl.cl: the one program holding every wavefront stage kernel, generated from the stage table
// (shared/stage_table.h): kernel <stage>(frame, the table's arguments) packs its arguments into a
// <stage>_args struct and runs the stage body (stages/<stage>.h) for work item get_global_id(0).
// Each body checks the item against its own count, so launches may round up to whole work-groups.
#include "stages/stages.h"

#define MCL_KERNEL_PARAM(type, name) , type name
#define MCL_KERNEL_VALUE(type, name) , name
#define MCL_STAGE_KERNEL(stage)                                                                    \
  __kernel void stage(__constant FrameParams* frame MCL_ARGS_##stage(MCL_KERNEL_PARAM)) {          \
    stage##_args a = {frame MCL_ARGS_##stage(MCL_KERNEL_VALUE)};                                   \
    stage_##stage(&a, (uint)get_global_id(0));                                                     \
  }
MCL_STAGES(MCL_STAGE_KERNEL)
