// stages.h: every wavefront stage body (one file each, kernels/stages/<stage>.h), in the order of
// MCL_STAGES (kernels/shared/stage_table.h). Included by kernels/montecl.cl, which turns each into
// a kernel, and by the host backend (host/render/host_backend.cpp), which runs them as loops.
#pragma once
#include "generate.h"
#include "intersect.h"
#include "shade_ao.h"
#include "shade_direct.h"
#include "shade_direct_hit.h"
#include "intersect_shadow.h"
#include "accumulate.h"
#include "record_aov.h"
#include "accumulate_aov.h"
#include "shade_path.h"
#include "path_gather.h"
// The fused stages, which run the others.
#include "wave_fused.h"
