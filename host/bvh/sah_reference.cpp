// sah_reference.cpp: full-sweep and object-median SAH reference builds (cost only), in double precision.
#include "bvh/sah_reference.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace montecl {
namespace {

using glm::vec3;
constexpr float kInf = INFINITY;

struct RefPrim {
  vec3 lo, hi, c;
};

double boxHalfArea(vec3 lo, vec3 hi) {
  glm::dvec3 d = glm::dvec3(hi) - glm::dvec3(lo);
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

double sweep(std::vector<RefPrim>& p, std::size_t b, std::size_t e, double rootArea, const BvhBuildOptions& o,
             std::vector<double>& rightArea) {
  const std::size_t n = e - b;
  vec3 lo(kInf), hi(-kInf);
  for (std::size_t i = b; i < e; ++i) {
    lo = glm::min(lo, p[i].lo);
    hi = glm::max(hi, p[i].hi);
  }
  const double area = boxHalfArea(lo, hi), leaf = double(o.intersectCost) * double(n);
  double best = kInf;
  int bestAxis = -1;
  std::size_t bestK = 0;
  for (int a = 0; a < 3 && n > 1; ++a) {
    std::sort(p.begin() + b, p.begin() + e, [a](const RefPrim& x, const RefPrim& y) { return x.c[a] < y.c[a]; });
    vec3 rl(kInf), rh(-kInf);
    for (std::size_t k = n; k-- > 1;) {
      rl = glm::min(rl, p[b + k].lo);
      rh = glm::max(rh, p[b + k].hi);
      rightArea[k] = boxHalfArea(rl, rh);
    }
    vec3 ll(kInf), lh(-kInf);
    for (std::size_t k = 1; k < n; ++k) {  // left = the first k
      ll = glm::min(ll, p[b + k - 1].lo);
      lh = glm::max(lh, p[b + k - 1].hi);
      double c = o.traversalCost + o.intersectCost * (boxHalfArea(ll, lh) * k + rightArea[k] * (n - k)) / area;
      if (c < best) {
        best = c;
        bestAxis = a;
        bestK = k;
      }
    }
  }
  const double rel = area / rootArea;
  if (bestAxis < 0 || (n <= std::size_t(o.maxLeafSize) && !(best < leaf))) return leaf * rel;
  std::sort(p.begin() + b, p.begin() + e,
            [bestAxis](const RefPrim& x, const RefPrim& y) { return x.c[bestAxis] < y.c[bestAxis]; });
  return o.traversalCost * rel + sweep(p, b, b + bestK, rootArea, o, rightArea) +
         sweep(p, b + bestK, e, rootArea, o, rightArea);
}

double median(std::vector<RefPrim>& p, std::size_t b, std::size_t e, double rootArea, const BvhBuildOptions& o) {
  const std::size_t n = e - b;
  vec3 lo(kInf), hi(-kInf), cl(kInf), ch(-kInf);
  for (std::size_t i = b; i < e; ++i) {
    lo = glm::min(lo, p[i].lo);
    hi = glm::max(hi, p[i].hi);
    cl = glm::min(cl, p[i].c);
    ch = glm::max(ch, p[i].c);
  }
  const double rel = boxHalfArea(lo, hi) / rootArea;
  if (n <= std::size_t(o.maxLeafSize)) return double(o.intersectCost) * double(n) * rel;
  const vec3 ext = ch - cl;
  const int a = (ext.x >= ext.y && ext.x >= ext.z) ? 0 : (ext.y >= ext.z ? 1 : 2);
  const std::size_t mid = b + n / 2;
  std::nth_element(p.begin() + b, p.begin() + mid, p.begin() + e,
                   [a](const RefPrim& x, const RefPrim& y) { return x.c[a] < y.c[a]; });
  return o.traversalCost * rel + median(p, b, mid, rootArea, o) + median(p, mid, e, rootArea, o);
}

// Bounds and centroids of tris; rootArea = the half area of their union.
std::vector<RefPrim> refPrims(const std::vector<SceneTriangle>& tris, double& rootArea) {
  std::vector<RefPrim> p;
  p.reserve(tris.size());
  vec3 lo(kInf), hi(-kInf);
  for (const SceneTriangle& t : tris) {
    RefPrim r;
    r.lo = glm::min(glm::min(t.v[0], t.v[1]), t.v[2]);
    r.hi = glm::max(glm::max(t.v[0], t.v[1]), t.v[2]);
    r.c = (r.lo + r.hi) * 0.5f;
    lo = glm::min(lo, r.lo);
    hi = glm::max(hi, r.hi);
    p.push_back(r);
  }
  rootArea = boxHalfArea(lo, hi);
  return p;
}

}  // namespace

double fullSweepSahCost(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options) {
  double rootArea = 0.0;
  std::vector<RefPrim> p = refPrims(tris, rootArea);
  if (p.empty()) return 0.0;
  std::vector<double> rightArea(p.size() + 1);
  return sweep(p, 0, p.size(), rootArea, options, rightArea);
}

double medianSplitSahCost(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options) {
  double rootArea = 0.0;
  std::vector<RefPrim> p = refPrims(tris, rootArea);
  if (p.empty()) return 0.0;
  return median(p, 0, p.size(), rootArea, options);
}

}  // namespace montecl
