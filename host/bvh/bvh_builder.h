// bvh_builder.h: internals of the binned-SAH builder, shared by its parts (bvh.h has the API):
//   bvh_build.cpp     entry point: checks, triangle references, output triangles, SAH cost
//   bvh_flatten.cpp   the recursion: split choice, depth-first node layout, parallel subtrees
//   bvh_binning.cpp   binned SAH over centroid bins and size-class bins (bvh_size_classes.h)
//   bvh_sweep.cpp     small nodes: exact SAH sweep; the object-median fallback
// The 8-wide collapse of the finished tree is bvh_wide.cpp.
#pragma once
#include <cstddef>
#include <cstdint>
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

// Smallest h with 2^h >= n: the height of a median-split subtree over n triangles.
inline int medianHeight(std::size_t n) {
  int h = 0;
  while ((std::size_t(1) << h) < n) ++h;
  return h;
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
