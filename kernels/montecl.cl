// montecl.cl: the one program holding every wavefront stage kernel.
#include "generate.cl"
#include "intersect.cl"
#include "shade_ao.cl"
#include "intersect_shadow.cl"
#include "accumulate.cl"
