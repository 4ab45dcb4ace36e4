// integrate.cl: its own program (built by host/integrate through the program cache) for
// `montecl integrate`: one work item per sample writes the sample's estimator term (f * volume or
// f / p); the host sums the terms in double.
#include "shared/integrands.h"

__kernel void integrate_terms(uint integrand, uint estimator, uint n, uint gridX, uint seed, uint k,
                              __global float* terms) {
  uint i = get_global_id(0);
  if (i >= n) return;
  terms[i] = mcl_integrate_term(integrand, estimator, i, n, gridX, seed, k);
}
