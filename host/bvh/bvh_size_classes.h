// bvh_size_classes.h: the size-class split of the binned SAH builder. Besides the centroid planes,
// the builder bins a node's triangles by size class (box area relative to the node's, in powers of
// two) and evaluates splitting the large ones from the small: it isolates a large triangle (a floor
// under a scanned model) whose centroid lies among many small ones, which no centroid plane can.
#pragma once
#include <algorithm>
#include <cmath>

namespace montecl {
namespace bvhbuild {

// Size classes: 6 beat 2, 4, 8 and 12 on the SAH cost of the shared scenes (bunny 3.25, Sibenik
// 47.99, Sponza 72.26 with 16 bins and C_isect 1; full sweep 3.83, 47.40, 75.66; without size
// classes 4.92, 48.10, 79.13). More classes offer more splits, yet the greedy top-down choice does
// worse.
constexpr int kSizeClasses = 6;

// Size classes for `bins` bins per axis (the class bins are the builder's fourth axis).
inline int sizeClassCount(int bins) { return std::min(bins, kSizeClasses); }

// Size class of a triangle of box half area `area` in a node of half area 1 / invNodeArea: 0 when
// the triangle's box has at least half the node's area, k when it has between 2^-(k+1) and 2^-k of
// it, the last class for the smallest (and for area 0).
inline int sizeClassOf(float area, float invNodeArea, int classes) {
  float r = area * invNodeArea;
  if (!(r > 0.0f)) return classes - 1;
  int e = 0;
  std::frexp(r, &e);  // r = m * 2^e, m in [0.5, 1)
  return std::clamp(-e, 0, classes - 1);
}

}  // namespace bvhbuild
}  // namespace montecl
