// montecl.cl: the one program holding every wavefront stage kernel.
#include "generate.cl"
#include "intersect.cl"
#include "shade_ao.cl"
#include "shade_direct.cl"
#include "shade_direct_hit.cl"
#include "intersect_shadow.cl"
#include "accumulate.cl"
