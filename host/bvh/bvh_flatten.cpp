// bvh_flatten.cpp: the builder's recursion. Each node picks its split (bvh_binning.cpp, or
// bvh_sweep.cpp for small nodes), and the tree is written depth-first into one BvhNode array with
// the two children of a node adjacent. Near the root, the right subtree of a large node is built
// on another thread into its own vector and appended, giving the single-threaded layout
// (buildChildPair, bvh_builder.h).
#include <algorithm>

#include "bvh/bvh_builder.h"

namespace montecl {
namespace bvhbuild {
int Builder::build(std::vector<BvhNode>& out, std::size_t idx, std::size_t begin, std::size_t end,
                 const Box& bounds, const Box& cbounds, int depth, int parallelLevels) const {
  writeBox(out[idx], bounds);
  std::size_t n = end - begin;
  bool mustSplit = n > static_cast<std::size_t>(maxLeaf);
  Box child[2], childC[2];
  std::size_t mid = 0;
  bool split = false;
  if (n > 1) {
    bool small = n <= kSweepMax;
    Split s = small ? findSweepSplit(begin, end, bounds) : findSahSplit(begin, end, bounds, cbounds);
    bool useSah = s.axis >= 0 && (mustSplit || s.cost < ci * static_cast<float>(n));
    if (useSah && depth + 1 + medianHeight(std::max(s.nLeft, n - s.nLeft)) > maxDepth) {
      useSah = false;  // that child could not be finished within the stack; split at the median
      mustSplit = true;
    }
    if (useSah) {
      mid = small ? partitionSweep(begin, end, s, child, childC)
                  : partitionSah(begin, end, bounds, cbounds, s, child, childC);
      split = true;
    } else if (mustSplit) {
      mid = partitionMedian(begin, end, cbounds, child, childC);
      split = true;
    }
  }
  if (!split) {
    out[idx].leftFirst = static_cast<std::uint32_t>(begin);
    out[idx].triCount = static_cast<std::uint32_t>(n);
    return depth;
  }
  std::size_t childBase = out.size();
  out[idx].leftFirst = static_cast<std::uint32_t>(childBase);
  out[idx].triCount = 0;
  out.emplace_back();
  out.emplace_back();
  return buildChildPair(
      out, childBase, n, parallelLevels, 2 * (end - mid) - 1,
      [&](std::vector<BvhNode>& nodes, std::size_t index, int side, int levels, bool) {
        return build(nodes, index, side ? mid : begin, side ? end : mid, child[side], childC[side], depth + 1, levels);
      },
      [] { return std::size_t(0); });  // (leaves index prims in place)
}

}  // namespace bvhbuild
}  // namespace montecl
