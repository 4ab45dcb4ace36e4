// bvh_spatial.cpp: spatial splits (see bvh_spatial.h): clipping a triangle reference at a plane,
// the spatial binning of a node (each reference chopped into the slabs it spans) and the
// partition of a node's references at the chosen plane.
#include "bvh/bvh_spatial.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace montecl {
namespace bvhbuild {

void splitReference(const PrimRef& r, const SceneTriangle& t, int axis, float pos, PrimRef& left,
                    PrimRef& right) {
  Box l, h;
  for (int k = 0; k < 3; ++k) {
    const glm::vec3& a = t.v[k];
    const glm::vec3& b = t.v[(k + 1) % 3];
    const float da = a[axis], db = b[axis];
    if (da <= pos) l.grow(a);
    if (da >= pos) h.grow(a);
    if ((da < pos && db > pos) || (da > pos && db < pos)) {
      const float f = (pos - da) / (db - da);
      glm::vec3 p = a + (b - a) * f;
      glm::vec3 e = (glm::abs(a) + glm::abs(b)) * (8.0f * FLT_EPSILON);
      p[axis] = pos;
      e[axis] = 0.0f;
      l.grow(p - e, p + e);
      h.grow(p - e, p + e);
    }
  }
  left = r;
  right = r;
  left.lo = glm::max(l.lo, r.lo);
  left.hi = glm::min(l.hi, r.hi);
  left.hi[axis] = std::min(left.hi[axis], pos);
  right.lo = glm::max(h.lo, r.lo);
  right.hi = glm::min(h.hi, r.hi);
  right.lo[axis] = std::max(right.lo[axis], pos);
}

float SpatialBinner::planePos(const Box& bounds, int axis, int k) const {
  const float w = (bounds.hi[axis] - bounds.lo[axis]) / static_cast<float>(bins);
  return bounds.lo[axis] + w * static_cast<float>(k + 1);
}

namespace {

// Slab range [first, last] of a reference along one axis (see SpatialBinner).
struct SlabRange {
  int first, last;
};

// first = number of planes <= lo, last = number of planes < hi (planes sorted, nPlanes of them):
// guessed from the slab width, then corrected against the planes themselves.
SlabRange slabsOf(const PrimRef& r, int axis, const float* planes, int nPlanes, float origin,
                  float invWidth) {
  const float lo = r.lo[axis], hi = r.hi[axis];
  auto guess = [&](float x) {
    float g = (x - origin) * invWidth;
    // NaN (never expected: find() skips axes without a finite invWidth) falls to slab 0 and is
    // corrected below, never converted to an integer.
    return !(g > 0.0f) ? 0 : (g >= float(nPlanes) ? nPlanes : static_cast<int>(g));
  };
  int first = guess(lo), last = guess(hi);
  while (first > 0 && planes[first - 1] > lo) --first;
  while (first < nPlanes && planes[first] <= lo) ++first;
  while (last > 0 && planes[last - 1] >= hi) --last;
  while (last < nPlanes && planes[last] < hi) ++last;
  return {first, std::max(first, last)};
}

}  // namespace

SpatialSplit SpatialBinner::find(const PrimRef* refs, std::size_t n, const Box& bounds, float ct,
                                 float ci) const {
  SpatialSplit best;
  const float area = bounds.halfArea();
  if (!(area > 0.0f) || bins < 2) return best;
  const float ciOverArea = ci / area;
  float planes[kMaxBins];
  Box box[kMaxBins];
  std::size_t enter[kMaxBins], exit[kMaxBins];
  for (int a = 0; a < 3; ++a) {
    if (!(bounds.hi[a] > bounds.lo[a])) continue;
    // An extent so thin (below bins / FLT_MAX, e.g. 2e-38) that its slabs' inverse width overflows
    // has no usable slab planes: 0 * inf made a NaN slab index and a read far outside the planes.
    const float invWidth = static_cast<float>(bins) / (bounds.hi[a] - bounds.lo[a]);
    if (!std::isfinite(invWidth)) continue;
    const int np = bins - 1;
    for (int k = 0; k < np; ++k) planes[k] = planePos(bounds, a, k);
    for (int k = 0; k < bins; ++k) {
      box[k] = Box();
      enter[k] = exit[k] = 0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const PrimRef& r = refs[i];
      SlabRange s = slabsOf(r, a, planes, np, bounds.lo[a], invWidth);
      ++enter[s.first];
      ++exit[s.last];
      PrimRef cur = r;
      for (int k = s.first; k < s.last; ++k) {
        PrimRef l, h;
        splitReference(cur, tris[r.id], a, planes[k], l, h);
        if (validRef(l)) box[k].grow(l.lo, l.hi);
        cur = h;
        if (!validRef(cur)) break;
      }
      if (validRef(cur)) box[s.last].grow(cur.lo, cur.hi);
    }
    sweepSahPlanes(
        bins, ct, ciOverArea, [&](int k) { return box[k]; }, [&](int k) { return enter[k]; },
        [&](int k) { return exit[k]; },
        [&](int k, float cost, std::size_t) {
          if (best.axis < 0 || cost < best.cost) {
            best.axis = a;
            best.plane = k;
            best.cost = cost;
          }
        });
  }
  return best;
}

void SpatialBinner::partition(const std::vector<PrimRef>& refs, const Box& bounds,
                              const SpatialSplit& s, std::vector<PrimRef>& left,
                              std::vector<PrimRef>& right) const {
  const int a = s.axis;
  const float pos = planePos(bounds, a, s.plane);
  for (const PrimRef& r : refs) {
    if (r.hi[a] <= pos) {
      left.push_back(r);
    } else if (r.lo[a] >= pos) {
      right.push_back(r);
    } else {
      PrimRef l, h;
      splitReference(r, tris[r.id], a, pos, l, h);
      bool lv = validRef(l), hv = validRef(h);
      if (lv) left.push_back(l);
      if (hv) right.push_back(h);
      if (!lv && !hv) left.push_back(r);  // cannot happen for a triangle inside r's box
    }
  }
}

}  // namespace bvhbuild
}  // namespace montecl
