// bvh_sbvh.cpp: the builder's recursion with spatial splits (BvhBuildOptions::splitBudget > 0).
// Like bvh_flatten.cpp (the same object splits, leaf rule, depth bound, depth-first layout with
// siblings adjacent and parallel right subtrees near the root), but each node owns its references
// in a vector, because a spatial split (bvh_spatial.h) hands a straddling triangle to both
// children. A node tries one when its best object split's children overlap by more than
// splitAlpha of the root's area, and takes it when it is cheaper (SAH) than the object split and
// both children have fewer references than the node. The budget of extra references is handed
// down deterministically: a node spends what its split duplicates, and its children share the
// rest in proportion to their reference counts (the tree does not depend on thread timing).
// Leaves list their input triangle ids in one array, in leaf order (Bvh::order).
#include <algorithm>
#include <limits>

#include "bvh/bvh_internal.h"
#include "bvh/bvh_spatial.h"

namespace montecl {
namespace bvhbuild {
namespace {

constexpr int kSpatialBins = 16;

void boundsOf(const std::vector<PrimRef>& refs, Box& box, Box& cbox) {
  for (const PrimRef& r : refs) {
    box.grow(r.lo, r.hi);
    cbox.grow(r.centroid());
  }
}

float overlapArea(const Box& a, const Box& b) {
  Box o;
  o.lo = glm::max(a.lo, b.lo);
  o.hi = glm::min(a.hi, b.hi);
  return o.halfArea();
}

struct SbvhBuilder {
  Builder base;  // costs, bins, leaf size and depth cap; prims set per node
  SpatialBinner spatial;
  float minOverlap;  // splitAlpha * the root's half area

  int build(std::vector<BvhNode>& out, std::vector<std::uint32_t>& ids, std::size_t idx,
            std::vector<PrimRef> refs, const Box& bounds, const Box& cbounds, int depth,
            std::size_t budget, int parallelLevels) const;
};

int SbvhBuilder::build(std::vector<BvhNode>& out, std::vector<std::uint32_t>& ids, std::size_t idx,
                       std::vector<PrimRef> refs, const Box& bounds, const Box& cbounds, int depth,
                       std::size_t budget, int parallelLevels) const {
  writeBox(out[idx], bounds);
  const std::size_t n = refs.size();
  const float ci = base.ci;
  bool mustSplit = n > static_cast<std::size_t>(base.maxLeaf);
  std::vector<PrimRef> side[2];
  Box child[2], childC[2];
  std::size_t budgetL = 0, budgetR = 0;
  bool split = false;
  if (n > 1) {
    Builder b = base;
    b.prims = refs.data();
    const bool small = n <= kSweepMax;
    Split s = small ? b.findSweepSplit(0, n, bounds) : b.findSahSplit(0, n, bounds, cbounds);
    std::size_t mid = 0;
    if (s.axis >= 0)
      mid = small ? b.partitionSweep(0, n, s, child, childC)
                  : b.partitionSah(0, n, bounds, cbounds, s, child, childC);
    // Spatial split: where the object split's children overlap (or there is none).
    if (budget > 0 && (s.axis < 0 || overlapArea(child[0], child[1]) > minOverlap)) {
      SpatialSplit ss = spatial.find(refs.data(), n, bounds, base.ct, ci);
      if (ss.axis >= 0 && (s.axis < 0 || ss.cost < s.cost) &&
          (mustSplit || ss.cost < ci * static_cast<float>(n))) {
        spatial.partition(refs, bounds, ss, side[0], side[1]);
        const std::size_t nl = side[0].size(), nr = side[1].size();
        const std::size_t extra = nl + nr - n;
        if (nl > 0 && nr > 0 && nl < n && nr < n && extra <= budget &&
            depth + 1 + medianHeight(std::max(nl, nr)) <= base.maxDepth) {
          split = true;
          const std::size_t rest = budget - extra;
          budgetL = static_cast<std::size_t>(double(rest) * double(nl) / double(nl + nr));
          budgetR = rest - budgetL;
          child[0] = child[1] = childC[0] = childC[1] = Box();
          boundsOf(side[0], child[0], childC[0]);
          boundsOf(side[1], child[1], childC[1]);
        } else {
          side[0].clear();
          side[1].clear();
        }
      }
    }
    if (!split) {
      bool useSah = s.axis >= 0 && (mustSplit || s.cost < ci * static_cast<float>(n));
      if (useSah && depth + 1 + medianHeight(std::max(s.nLeft, n - s.nLeft)) > base.maxDepth) {
        useSah = false;  // that child could not be finished within the stack
        mustSplit = true;
      }
      if (!useSah && mustSplit) {
        child[0] = child[1] = childC[0] = childC[1] = Box();
        mid = b.partitionMedian(0, n, cbounds, child, childC);
      }
      if (useSah || mustSplit) {
        split = true;
        // The left side keeps the node's vector (freed when that child splits in turn): 1.5x the
        // node's references at the peak instead of 2x.
        side[1].assign(refs.begin() + static_cast<std::ptrdiff_t>(mid), refs.end());
        refs.resize(mid);
        side[0].swap(refs);
        budgetL = static_cast<std::size_t>(double(budget) * double(mid) / double(n));
        budgetR = budget - budgetL;
      }
    }
  }
  if (!split) {
    out[idx].leftFirst = static_cast<std::uint32_t>(ids.size());
    out[idx].triCount = static_cast<std::uint32_t>(n);
    for (const PrimRef& r : refs) ids.push_back(r.id);
    return depth;
  }
  std::vector<PrimRef>().swap(refs);  // the children own the references now
  const std::size_t childBase = out.size();
  out[idx].leftFirst = static_cast<std::uint32_t>(childBase);
  out[idx].triCount = 0;
  out.emplace_back();
  out.emplace_back();
  // The right subtree built apart (own) lists its leaves' ids apart too: appended afterwards,
  // its leaves' triangle ranges moved by the left part's id count.
  std::vector<std::uint32_t> idsRight;
  const std::size_t budgets[2] = {budgetL, budgetR};
  return buildChildPair(
      out, childBase, n, parallelLevels, 2 * side[1].size(),
      [&, depth](std::vector<BvhNode>& nodes, std::size_t index, int s, int levels, bool own) {
        return build(nodes, own ? idsRight : ids, index, std::move(side[s]), child[s], childC[s], depth + 1,
                     budgets[s], levels);
      },
      [&] {
        const std::size_t idOffset = ids.size();
        ids.insert(ids.end(), idsRight.begin(), idsRight.end());
        return idOffset;
      });
}

}  // namespace

int buildSpatialTree(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options,
                     int maxDepth, std::vector<PrimRef> prims, const Box& rootBox, const Box& rootC,
                     int parallelLevels, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& order) {
  const std::size_t n = prims.size();
  const std::size_t budget = static_cast<std::size_t>(double(options.splitBudget) * double(n));
  SbvhBuilder sb{Builder{nullptr, options.bins, options.maxLeafSize, options.traversalCost,
                         options.intersectCost, maxDepth},
                 SpatialBinner{tris.data(), kSpatialBins},
                 options.splitAlpha * rootBox.halfArea()};
  nodes.reserve(2 * (n + budget));
  order.reserve(n + budget);
  nodes.emplace_back();
  return sb.build(nodes, order, 0, std::move(prims), rootBox, rootC, 0, budget, parallelLevels);
}

}  // namespace bvhbuild
}  // namespace montecl
