// bvh_builder.h: internals of the binned-SAH builder, shared by its parts (bvh.h has the API):
//   bvh_build.cpp     entry point: checks, triangle references, output triangles, SAH cost
//   bvh_flatten.cpp   the recursion: split choice, depth-first node layout (buildChildPair here:
//                     the children, the right one on its own thread near the root)
//   bvh_binning.cpp   binned SAH over centroid bins and size-class bins (bvh_size_classes.h)
//   bvh_sweep.cpp     small nodes: exact SAH sweep; the object-median fallback
// The 8-wide collapse of the finished tree is bvh_wide.cpp.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <future>
#include <limits>
#include <vector>

#include "bvh/bvh.h"

namespace montecl {
namespace bvhbuild {

constexpr int kMaxDepth = MCL_BVH_STACK_SIZE - 1;  // deepest leaf, in edges from the root
constexpr int kMaxLeafCap = 16;
constexpr int kMaxBins = 256;
constexpr int kSplitAxes = 4;    // x, y, z centroid bins and the size-class bins
constexpr std::size_t kSweepMax = 16;  // nodes this small evaluate every object split exactly
constexpr std::size_t kParallelMin = std::size_t(1) << 16;  // smallest subtree given its own thread
constexpr std::size_t kMinPrimsPerThread = std::size_t(1) << 13;  // per-triangle passes: inline below

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};
  void grow(const glm::vec3& l, const glm::vec3& h) {
    lo = glm::min(lo, l);
    hi = glm::max(hi, h);
  }
  void grow(const glm::vec3& p) { grow(p, p); }
  void grow(const Box& b) { grow(b.lo, b.hi); }
  float halfArea() const {
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return 0.0f;
    glm::vec3 d = hi - lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

// A flattened node's box (the object and the spatial-split builds write nodes alike).
inline void writeBox(BvhNode& n, const Box& b) {
  n.minX = b.lo.x; n.minY = b.lo.y; n.minZ = b.lo.z;
  n.maxX = b.hi.x; n.maxY = b.hi.y; n.maxZ = b.hi.z;
}

// Per-triangle build reference: bounds and the input index. Partitioned in place.
struct PrimRef {
  glm::vec3 lo;
  std::uint32_t id;
  glm::vec3 hi;
  std::uint32_t pad;
  glm::vec3 centroid() const { return (lo + hi) * 0.5f; }
};
static_assert(sizeof(PrimRef) == 32, "PrimRef is one half cache line");

// Trivially constructible (no initialisers) so the per-node bin arrays cost nothing until used.
struct Bin {
  glm::vec3 lo, hi;
  std::uint32_t count;
};

struct Split {
  int axis = -1;
  int bin = 0;          // left side: centroid bin <= bin
  float cost = 0.0f;
  std::size_t nLeft = 0;
};

// The SAH cost of a split (ciOverArea: C_isect over the node's half area): C_trav plus C_isect
// times each side's half area and primitive count, over the node's. Written once: the binned, the
// spatial and the small-node sweeps compare costs with each other and with a leaf's.
inline float sahSplitCost(float ct, float ciOverArea, float leftArea, std::size_t leftCount, float rightArea,
                          std::size_t rightCount) {
  return ct + ciOverArea * (leftArea * static_cast<float>(leftCount) + rightArea * static_cast<float>(rightCount));
}

// One axis of a SAH sweep over `bins` (at most kMaxBins) bins in order: plane k < bins - 1 has bins
// 0..k on its left. boxOf(k) is bin k's box, enters(k) the references whose left end lies in
// it and exits(k) those whose right end does (both the bin's count for an object split, where a
// reference lies in one bin). Calls visit(k, cost, leftCount) for every plane with references on
// both sides, left to right.
template <class BoxOf, class Enters, class Exits, class Visit>
void sweepSahPlanes(int bins, float ct, float ciOverArea, const BoxOf& boxOf, const Enters& enters,
                    const Exits& exits, const Visit& visit) {
  float rightArea[kMaxBins];
  std::size_t rightCount[kMaxBins];
  Box acc;
  std::size_t cnt = 0;
  for (int k = bins - 1; k > 0; --k) {  // right of plane k - 1: bins k..bins-1
    acc.grow(boxOf(k));
    cnt += exits(k);
    rightArea[k] = acc.halfArea();
    rightCount[k] = cnt;
  }
  acc = Box();
  cnt = 0;
  for (int k = 0; k < bins - 1; ++k) {  // plane k: left bins 0..k
    acc.grow(boxOf(k));
    cnt += enters(k);
    if (cnt == 0 || rightCount[k + 1] == 0) continue;
    visit(k, sahSplitCost(ct, ciOverArea, acc.halfArea(), cnt, rightArea[k + 1], rightCount[k + 1]), cnt);
  }
}

// Smallest h with 2^h >= n: the height of a median-split subtree over n triangles.
inline int medianHeight(std::size_t n) {
  int h = 0;
  while ((std::size_t(1) << h) < n) ++h;
  return h;
}

// The two children of a split node of n references, at out[childBase] and out[childBase + 1]
// (allocated), built by buildSide(nodes, index, side, levels, own) (side 0 left, 1 right; returns
// the deepest leaf's depth) in the layout [left, right, left's descendants, right's descendants].
// Near the root (levels > 0 and n >= kParallelMin) the right subtree is built on another thread
// into its own vector (own: true, its root at index 0, rightNodes reserved) while this thread
// builds the left one in place; it is then appended, its child links moved by the left part's
// nodes and its leaves' first triangle by appendRightLeaves() (called once both are built; 0
// where leaves index the triangles in place), so the tree is the one a single thread builds.
// Shared by the object build (bvh_flatten.cpp) and the spatial-split build (bvh_sbvh.cpp).
template <class BuildSide, class AppendRightLeaves>
int buildChildPair(std::vector<BvhNode>& out, std::size_t childBase, std::size_t n, int levels,
                   std::size_t rightNodes, const BuildSide& buildSide, const AppendRightLeaves& appendRightLeaves) {
  if (levels <= 0 || n < kParallelMin) {
    const int dl = buildSide(out, childBase, 0, levels, false);
    const int dr = buildSide(out, childBase + 1, 1, levels, false);
    return std::max(dl, dr);
  }
  std::vector<BvhNode> vr;
  auto right = std::async(std::launch::async, [&] {
    vr.reserve(rightNodes);
    vr.emplace_back();
    return buildSide(vr, 0, 1, levels - 1, true);
  });
  const int dl = buildSide(out, childBase, 0, levels - 1, false);
  const int dr = right.get();
  const std::size_t offset = out.size() - 1, leafOffset = appendRightLeaves();  // vr[k] (k >= 1) lands at out[offset + k]
  const auto remap = [offset, leafOffset](BvhNode node) {
    node.leftFirst = static_cast<std::uint32_t>(node.leftFirst + (node.triCount == 0 ? offset : leafOffset));
    return node;
  };
  out[childBase + 1] = remap(vr[0]);
  for (std::size_t k = 1; k < vr.size(); ++k) out.push_back(remap(vr[k]));
  return std::max(dl, dr);
}

struct Builder {
  PrimRef* prims;
  int bins;
  int maxLeaf;
  float ct, ci;
  int maxDepth;

  // Builds the subtree over prims[begin, end) rooted at out[idx] (already allocated), appending
  // its descendants to out depth-first with siblings adjacent. Returns the deepest leaf's depth.
  // (bvh_flatten.cpp)
  int build(std::vector<BvhNode>& out, std::size_t idx, std::size_t begin, std::size_t end,
            const Box& bounds, const Box& cbounds, int depth, int parallelLevels) const;

  // Binned SAH (bvh_binning.cpp).
  int sizeClasses() const;
  int binOf(float c, float lo, float scale) const;
  int sizeBinOf(const PrimRef& p, float invArea) const;
  Split findSahSplit(std::size_t begin, std::size_t end, const Box& bounds, const Box& cbounds) const;
  std::size_t partitionSah(std::size_t begin, std::size_t end, const Box& bounds, const Box& cbounds,
                           const Split& s, Box child[2], Box childC[2]) const;

  // Nodes of at most kSweepMax triangles, and the median fallback (bvh_sweep.cpp).
  void sortSmall(std::size_t begin, std::size_t n, int a, std::uint8_t* idx) const;
  Split findSweepSplit(std::size_t begin, std::size_t end, const Box& bounds) const;
  std::size_t partitionSweep(std::size_t begin, std::size_t end, const Split& s, Box child[2],
                             Box childC[2]) const;
  std::size_t partitionMedian(std::size_t begin, std::size_t end, const Box& cbounds, Box child[2],
                              Box childC[2]) const;
};

}  // namespace bvhbuild
}  // namespace montecl
