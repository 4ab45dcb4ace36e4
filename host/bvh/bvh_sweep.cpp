// bvh_sweep.cpp: nodes of at most kSweepMax triangles sort their centroids on each axis and
// evaluate every object split (exact, and cheaper than binning at that size); nodes SAH cannot
// split are cut at the object median along the widest centroid axis.
#include <algorithm>

#include "bvh/bvh_builder.h"

namespace montecl {
namespace bvhbuild {

// Stable insertion sort of the n (<= kSweepMax) triangles at begin by centroid along axis a.
void Builder::sortSmall(std::size_t begin, std::size_t n, int a, std::uint8_t* idx) const {
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t v = static_cast<std::uint8_t>(i);
    float c = prims[begin + v].centroid()[a];
    std::size_t j = i;
    for (; j > 0 && prims[begin + idx[j - 1]].centroid()[a] > c; --j) idx[j] = idx[j - 1];
    idx[j] = v;
  }
}

// Exact SAH for a small node: every object split along each axis (nLeft = left count).
Split Builder::findSweepSplit(std::size_t begin, std::size_t end, const Box& bounds) const {
  Split best;
  float area = bounds.halfArea();
  if (!(area > 0.0f)) return best;
  std::size_t n = end - begin;
  float ciOverArea = ci / area;
  std::uint8_t idx[kSweepMax];
  for (int a = 0; a < 3; ++a) {
    sortSmall(begin, n, a, idx);
    // The sorted triangles as n bins of one each: plane k has sorted 0..k on its left.
    const auto one = [](int) { return std::size_t(1); };
    sweepSahPlanes(
        int(n), ct, ciOverArea,
        [&](int k) { return Box{prims[begin + idx[k]].lo, prims[begin + idx[k]].hi}; }, one, one,
        [&](int, float cost, std::size_t nLeft) {
          if (best.axis < 0 || cost < best.cost) {
            best.axis = a;
            best.cost = cost;
            best.nLeft = nLeft;
          }
        });
  }
  return best;
}

// Reorders a small node along the sweep split's axis; returns the first right index.
std::size_t Builder::partitionSweep(std::size_t begin, std::size_t end, const Split& s, Box child[2],
                                  Box childC[2]) const {
  std::size_t n = end - begin;
  std::uint8_t idx[kSweepMax];
  PrimRef tmp[kSweepMax];
  sortSmall(begin, n, s.axis, idx);
  for (std::size_t i = 0; i < n; ++i) tmp[i] = prims[begin + idx[i]];
  for (std::size_t i = 0; i < n; ++i) {
    prims[begin + i] = tmp[i];
    int side = i < s.nLeft ? 0 : 1;
    child[side].grow(tmp[i].lo, tmp[i].hi);
    childC[side].grow(tmp[i].centroid());
  }
  return begin + s.nLeft;
}

// Object median along the widest centroid axis (or just the middle of the range when every
// centroid coincides); left gets floor(n/2) triangles.
std::size_t Builder::partitionMedian(std::size_t begin, std::size_t end, const Box& cbounds, Box child[2],
                                   Box childC[2]) const {
  glm::vec3 ext = cbounds.hi - cbounds.lo;
  int a = (ext.x >= ext.y && ext.x >= ext.z) ? 0 : (ext.y >= ext.z ? 1 : 2);
  std::size_t mid = begin + (end - begin) / 2;
  if (ext[a] > 0.0f) {
    std::nth_element(prims + begin, prims + mid, prims + end,
                     [a](const PrimRef& p, const PrimRef& q) {
                       return p.centroid()[a] < q.centroid()[a];
                     });
  }
  for (std::size_t i = begin; i < end; ++i) {
    int side = i < mid ? 0 : 1;
    child[side].grow(prims[i].lo, prims[i].hi);
    childC[side].grow(prims[i].centroid());
  }
  return mid;
}

}  // namespace bvhbuild
}  // namespace montecl
