// bvh_visit_counts.h: traversal work per ray of the 8-wide layout, counted on the host: interior nodes
// visited and leaves tested, by the loop of wide_closest_hit / wide_any_hit
// (kernels/shared/traverse_wide.h) with counters added. Deterministic, unlike Mrays/s on a
// loaded machine: `montecl bench` reports it beside the timings. Reads the BVH and rays only.
#pragma once
#include <vector>

#include "bvh/bvh.h"

namespace montecl {

struct VisitCounts {
  double nodes = 0.0;   // interior (wide) nodes visited per ray
  double leaves = 0.0;  // leaves tested per ray
};

// Mean counts over rays (dir.w = tmax) for closest hit, or any hit when anyHit; alpha may be
// null. On threadCount threads (the result does not depend on it).
VisitCounts countWideVisits(const Bvh& bvh, const std::vector<Ray>& rays, bool anyHit,
                            const AlphaScene* alpha = nullptr, unsigned threadCount = 1);

}  // namespace montecl
