// bvh_build.cpp: binned-SAH BVH builder on the host, flattened depth-first into 32-byte BvhNodes.
//
// Cost model (surface area heuristic). For a node N with half surface area A(N):
//   cost(leaf with n triangles)  = Ci * n
//   cost(split into L and R)     = Ct + Ci * (A(L) * n(L) + A(R) * n(R)) / A(N)
// with Ct = BvhBuildOptions::traversalCost (default 1) and Ci = intersectCost (default 0.5: the
// traversal tests a leaf's triangles four at a time). The reported Bvh::sahCost is the cost of the
// whole tree, sum over interior nodes of Ct * A(n)/A(root) plus sum over leaves of
// Ci * count(n) * A(n)/A(root).
//
// Build. A node of more than 16 triangles bins their bounding-box centroids into `bins` (default
// 32, 2..256) equal bins along each axis of the centroid bounds and evaluates the bins-1 planes per
// axis, plus the splits of large from small triangles by size class (box area relative to the
// node's, in powers of two); a node of at most 16 sorts its centroids on each axis and evaluates every object split
// (exact, and cheaper than binning at that size). A node with at most maxLeafSize (default 4,
// 1..16) triangles becomes a leaf unless its best split is cheaper than the leaf; a larger node is
// always split, by its best SAH split even when a leaf would be cheaper, so no leaf ever holds more
// than maxLeafSize triangles (hard cap 16). When SAH finds no split (all centroids coincide, or
// the node's box has zero area) the node is split at the object median along the widest centroid
// axis, or into the two halves of its range when every centroid is the same point. Depth is
// bounded: every node at depth d with n triangles satisfies d + ceil(log2 n) <= 63, because a SAH
// split that would break that for a child is replaced by a median split (which halves n), so no
// leaf is deeper than 63 edges below the root (< MCL_BVH_STACK_SIZE = 64 stack entries).
//
// Memory: one 32-byte reference per triangle (bounds + input index) partitioned in place, the node
// array (reserved at 2n-1 entries but only touched as used), then the 48-byte output triangles and
// the 4-byte order: about 125 bytes per triangle at the peak besides the input (the node count
// depends on the scene: 1 to 1.9 per triangle with the default costs). Near the root, the right
// subtree of a node with at least 64k triangles is built on another thread (one such level per
// doubling of std::thread::hardware_concurrency) into its own vector and appended; the result is
// identical to the single-threaded build.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "bvh/bvh.h"
#include "bvh/bvh_internal.h"
#include "util/parallel_for.h"

namespace montecl {
namespace {

constexpr int kMaxDepth = MCL_BVH_STACK_SIZE - 1;  // deepest leaf, in edges from the root
constexpr int kMaxLeafCap = 16;
constexpr int kMaxBins = 256;
constexpr int kSplitAxes = 4;    // x, y, z centroid bins and the size-class bins
// Size classes: 6 beat 2, 4, 8 and 12 on the SAH cost of the shared scenes (bunny 3.25, Sibenik
// 47.99, Sponza 72.26 with 16 bins and C_isect 1; full sweep 3.83, 47.40, 75.66; without size
// classes 4.92, 48.10, 79.13). More classes offer more splits, yet the greedy top-down choice does
// worse.
constexpr int kSizeClasses = 6;
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
int medianHeight(std::size_t n) {
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

  int sizeClasses() const { return std::min(bins, kSizeClasses); }
  int binOf(float c, float lo, float scale) const {
    int b = static_cast<int>((c - lo) * scale);
    return b < bins ? b : bins - 1;
  }

  // Size class of p in a node of half area 1 / invArea: 0 when p's box has at least half the
  // node's area, k when it has between 2^-(k+1) and 2^-k of it, the last class for the smallest
  // (and for area 0).
  int sizeBinOf(const PrimRef& p, float invArea) const {
    Box b{p.lo, p.hi};
    float r = b.halfArea() * invArea;
    if (!(r > 0.0f)) return sizeClasses() - 1;
    int e = 0;
    std::frexp(r, &e);  // r = m * 2^e, m in [0.5, 1)
    return std::clamp(-e, 0, sizeClasses() - 1);
  }

  // Best binned SAH split over prims[begin, end); axis -1 when none separates them. Axes 0-2 bin
  // centroids along x, y, z; "axis" 3 bins the triangles by size class (sizeBinOf) and splits the
  // large ones from the small: it isolates a large triangle (a floor under a scanned model) whose
  // centroid lies among many small ones, which no centroid plane can (found on the bunny scene:
  // SAH cost 4.92 against 3.83 for a full sweep, with 16 or 128 bins alike, C_isect 1).
  Split findSahSplit(std::size_t begin, std::size_t end, const Box& bounds, const Box& cbounds) const {
    Split best;
    float area = bounds.halfArea();
    if (!(area > 0.0f)) return best;
    const float invArea = 1.0f / area;
    float scale[3];
    bool ok[kSplitAxes];
    for (int a = 0; a < 3; ++a) {
      float ext = cbounds.hi[a] - cbounds.lo[a];
      scale[a] = ext > 0.0f ? static_cast<float>(bins) / ext : 0.0f;
      ok[a] = ext > 0.0f && std::isfinite(scale[a]);
    }
    ok[3] = true;
    Bin binArr[kSplitAxes][kMaxBins];
    const Box empty;
    for (int a = 0; a < kSplitAxes; ++a)
      for (int k = 0; k < bins; ++k) binArr[a][k] = Bin{empty.lo, empty.hi, 0};
    for (std::size_t i = begin; i < end; ++i) {
      const PrimRef& p = prims[i];
      glm::vec3 c = p.centroid();
      for (int a = 0; a < 3; ++a) {
        if (!ok[a]) continue;
        Bin& b = binArr[a][binOf(c[a], cbounds.lo[a], scale[a])];
        b.lo = glm::min(b.lo, p.lo);
        b.hi = glm::max(b.hi, p.hi);
        ++b.count;
      }
      Bin& b = binArr[3][sizeBinOf(p, invArea)];
      b.lo = glm::min(b.lo, p.lo);
      b.hi = glm::max(b.hi, p.hi);
      ++b.count;
    }
    float rightArea[kMaxBins];
    std::size_t rightCount[kMaxBins];
    std::size_t n = end - begin;
    float ciOverArea = ci / area;
    for (int a = 0; a < kSplitAxes; ++a) {
      if (!ok[a]) continue;
      Box acc;
      std::size_t cnt = 0;
      for (int k = bins - 1; k > 0; --k) {  // rightArea[k]: bins k..bins-1
        acc.grow(binArr[a][k].lo, binArr[a][k].hi);
        cnt += binArr[a][k].count;
        rightArea[k] = acc.halfArea();
        rightCount[k] = cnt;
      }
      acc = Box();
      cnt = 0;
      for (int k = 0; k < bins - 1; ++k) {  // split between bin k and k+1
        acc.grow(binArr[a][k].lo, binArr[a][k].hi);
        cnt += binArr[a][k].count;
        if (cnt == 0 || cnt == n) continue;
        float cost = ct + ciOverArea * (acc.halfArea() * static_cast<float>(cnt) +
                                        rightArea[k + 1] * static_cast<float>(rightCount[k + 1]));
        if (best.axis < 0 || cost < best.cost) {
          best.axis = a;
          best.bin = k;
          best.cost = cost;
          best.nLeft = cnt;
        }
      }
    }
    return best;
  }

  // Stable insertion sort of the n (<= kSweepMax) triangles at begin by centroid along axis a.
  void sortSmall(std::size_t begin, std::size_t n, int a, std::uint8_t* idx) const {
    for (std::size_t i = 0; i < n; ++i) {
      std::uint8_t v = static_cast<std::uint8_t>(i);
      float c = prims[begin + v].centroid()[a];
      std::size_t j = i;
      for (; j > 0 && prims[begin + idx[j - 1]].centroid()[a] > c; --j) idx[j] = idx[j - 1];
      idx[j] = v;
    }
  }

  // Exact SAH for a small node: every object split along each axis (nLeft = left count).
  Split findSweepSplit(std::size_t begin, std::size_t end, const Box& bounds) const {
    Split best;
    float area = bounds.halfArea();
    if (!(area > 0.0f)) return best;
    std::size_t n = end - begin;
    float ciOverArea = ci / area;
    std::uint8_t idx[kSweepMax];
    float rightArea[kSweepMax];
    for (int a = 0; a < 3; ++a) {
      sortSmall(begin, n, a, idx);
      Box acc;
      for (std::size_t k = n - 1; k > 0; --k) {  // rightArea[k]: sorted k..n-1
        acc.grow(prims[begin + idx[k]].lo, prims[begin + idx[k]].hi);
        rightArea[k] = acc.halfArea();
      }
      acc = Box();
      for (std::size_t k = 1; k < n; ++k) {  // left: sorted 0..k-1
        acc.grow(prims[begin + idx[k - 1]].lo, prims[begin + idx[k - 1]].hi);
        float cost = ct + ciOverArea * (acc.halfArea() * static_cast<float>(k) +
                                        rightArea[k] * static_cast<float>(n - k));
        if (best.axis < 0 || cost < best.cost) {
          best.axis = a;
          best.cost = cost;
          best.nLeft = k;
        }
      }
    }
    return best;
  }

  // Reorders a small node along the sweep split's axis; returns the first right index.
  std::size_t partitionSweep(std::size_t begin, std::size_t end, const Split& s, Box child[2],
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

  // Partitions prims[begin, end) by the split; returns the first right index and child bounds.
  std::size_t partitionSah(std::size_t begin, std::size_t end, const Box& bounds, const Box& cbounds,
                           const Split& s, Box child[2], Box childC[2]) const {
    int a = s.axis;
    float lo = a < 3 ? cbounds.lo[a] : 0.0f;
    float scale = a < 3 ? static_cast<float>(bins) / (cbounds.hi[a] - cbounds.lo[a]) : 0.0f;
    float invArea = 1.0f / bounds.halfArea();
    auto isLeft = [&](const PrimRef& p) {
      return (a < 3 ? binOf(p.centroid()[a], lo, scale) : sizeBinOf(p, invArea)) <= s.bin;
    };
    auto add = [&](int side, const PrimRef& p) {
      child[side].grow(p.lo, p.hi);
      childC[side].grow(p.centroid());
    };
    std::size_t i = begin, j = end;
    for (;;) {
      while (i < j && isLeft(prims[i])) add(0, prims[i++]);
      while (i < j && !isLeft(prims[j - 1])) add(1, prims[--j]);
      if (i >= j) break;
      std::swap(prims[i], prims[j - 1]);
      add(0, prims[i++]);
      add(1, prims[--j]);
    }
    return i;
  }

  // Object median along the widest centroid axis (or just the middle of the range when every
  // centroid coincides); left gets floor(n/2) triangles.
  std::size_t partitionMedian(std::size_t begin, std::size_t end, const Box& cbounds, Box child[2],
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

  static void writeBox(BvhNode& n, const Box& b) {
    n.minX = b.lo.x; n.minY = b.lo.y; n.minZ = b.lo.z;
    n.maxX = b.hi.x; n.maxY = b.hi.y; n.maxZ = b.hi.z;
  }

  // Builds the subtree over prims[begin, end) rooted at out[idx] (already allocated), appending
  // its descendants to out depth-first with siblings adjacent. Returns the deepest leaf's depth.
  int build(std::vector<BvhNode>& out, std::size_t idx, std::size_t begin, std::size_t end,
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
    if (parallelLevels > 0 && n >= kParallelMin) {
      // The right subtree is built on another thread into its own vector while this thread builds
      // the left one in place; the right one is then appended, giving the sequential layout:
      // [left, right, left's descendants, right's descendants].
      std::vector<BvhNode> vr;
      auto right = std::async(std::launch::async, [&, depth, parallelLevels] {
        vr.reserve(2 * (end - mid) - 1);
        vr.emplace_back();
        return build(vr, 0, mid, end, child[1], childC[1], depth + 1, parallelLevels - 1);
      });
      int dl = build(out, childBase, begin, mid, child[0], childC[0], depth + 1, parallelLevels - 1);
      int dr = right.get();
      std::size_t offset = out.size() - 1;  // vr[k] (k >= 1) lands at out[offset + k]
      auto remap = [offset](BvhNode node) {
        if (node.triCount == 0) node.leftFirst = static_cast<std::uint32_t>(node.leftFirst + offset);
        return node;
      };
      out[childBase + 1] = remap(vr[0]);
      for (std::size_t k = 1; k < vr.size(); ++k) out.push_back(remap(vr[k]));
      return std::max(dl, dr);
    }
    int dl = build(out, childBase, begin, mid, child[0], childC[0], depth + 1, parallelLevels);
    int dr = build(out, childBase + 1, mid, end, child[1], childC[1], depth + 1, parallelLevels);
    return std::max(dl, dr);
  }
};

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}


}  // namespace

WideNode emptyWideNode() {
  WideNode w;
  const float inf = std::numeric_limits<float>::infinity();
  for (int r = 0; r < 6; ++r)
    for (int i = 0; i < MCL_WIDE_WIDTH; ++i) w.bounds[r][i] = (r % 2 == 0) ? inf : -inf;
  for (int i = 0; i < MCL_WIDE_WIDTH; ++i) w.child[i] = MCL_WIDE_EMPTY;
  return w;
}

BvhNode emptyBinaryNode() {
  const float inf = std::numeric_limits<float>::infinity();
  BvhNode n;
  n.minX = n.minY = n.minZ = inf;
  n.maxX = n.maxY = n.maxZ = -inf;
  n.leftFirst = 0;
  n.triCount = 0;
  return n;
}

namespace {

// Collapses the binary tree into MCL_WIDE_WIDTH-wide nodes: each wide node takes the binary node's
// two children and, while it has fewer than MCL_WIDE_WIDTH, replaces its interior child of largest surface area by that
// child's two children. Wide nodes are laid out depth-first; leaves keep their triangle ranges.
void collapseWide(Bvh& bvh) {
  const std::vector<BvhNode>& nodes = bvh.nodes;
  std::vector<WideNode>& wide = bvh.wide;
  wide.clear();
  if (bvh.triangles.size() > (std::size_t(1) << 27))
    throw std::invalid_argument("buildBvh: the wide BVH holds at most 2^27 triangles");
  auto area = [](const BvhNode& b) {
    float dx = b.maxX - b.minX, dy = b.maxY - b.minY, dz = b.maxZ - b.minZ;
    return dx * dy + dy * dz + dz * dx;
  };
  wide.reserve(nodes.size() / 4 + 1);
  wide.push_back(emptyWideNode());
  if (nodes.empty()) return;
  struct Item {
    std::uint32_t binary, wide;
  };
  std::vector<Item> todo{{0u, 0u}};
  while (!todo.empty()) {
    Item it = todo.back();
    todo.pop_back();
    std::uint32_t kids[MCL_WIDE_WIDTH];
    int k = 0;
    const BvhNode& b = nodes[it.binary];
    if (b.triCount > 0) {
      kids[k++] = it.binary;  // a leaf root: one child, the whole tree
    } else {
      kids[k++] = b.leftFirst;
      kids[k++] = b.leftFirst + 1;
      while (k < MCL_WIDE_WIDTH) {
        int best = -1;
        float bestArea = -1.0f;
        for (int i = 0; i < k; ++i)
          if (nodes[kids[i]].triCount == 0 && area(nodes[kids[i]]) > bestArea) {
            best = i;
            bestArea = area(nodes[kids[i]]);
          }
        if (best < 0) break;
        std::uint32_t c = nodes[kids[best]].leftFirst;
        for (int i = k; i > best + 1; --i) kids[i] = kids[i - 1];  // keep left-to-right order
        kids[best] = c;
        kids[best + 1] = c + 1;
        ++k;
      }
    }
    std::uint32_t pendingFrom = static_cast<std::uint32_t>(todo.size());
    for (int i = 0; i < k; ++i) {
      const BvhNode& c = nodes[kids[i]];
      WideNode& w = wide[it.wide];
      w.bounds[0][i] = c.minX;
      w.bounds[1][i] = c.maxX;
      w.bounds[2][i] = c.minY;
      w.bounds[3][i] = c.maxY;
      w.bounds[4][i] = c.minZ;
      w.bounds[5][i] = c.maxZ;
      if (c.triCount > 0) {
        w.child[i] = MCL_WIDE_LEAF | (c.leftFirst << 4) | (c.triCount - 1);
      } else {
        std::uint32_t idx = static_cast<std::uint32_t>(wide.size());
        wide[it.wide].child[i] = idx;
        wide.push_back(emptyWideNode());  // may reallocate: w is not used after this
        todo.push_back({kids[i], idx});
      }
    }
    std::reverse(todo.begin() + pendingFrom, todo.end());  // depth-first, left child first
  }
}

}  // namespace

Bvh buildBvh(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options) {
  return buildBvhCapped(tris, options, kMaxDepth);
}

Bvh buildBvhCapped(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options,
                   int maxDepth) {
  auto t0 = std::chrono::steady_clock::now();
  if (tris.empty()) throw std::invalid_argument("buildBvh: no triangles");
  if (tris.size() > (std::size_t(1) << 31))
    throw std::invalid_argument("buildBvh: more than 2^31 triangles");
  if (options.bins < 2 || options.bins > kMaxBins)
    throw std::invalid_argument("buildBvh: bins must be in [2, " + std::to_string(kMaxBins) + "]");
  if (options.maxLeafSize < 1 || options.maxLeafSize > kMaxLeafCap)
    throw std::invalid_argument("buildBvh: maxLeafSize must be in [1, " +
                                std::to_string(kMaxLeafCap) + "]");
  if (!(options.traversalCost > 0.0f) || !(options.intersectCost > 0.0f) ||
      !std::isfinite(options.traversalCost) || !std::isfinite(options.intersectCost))
    throw std::invalid_argument("buildBvh: traversal and intersection costs must be finite and > 0");
  if (maxDepth > kMaxDepth || maxDepth < medianHeight(tris.size()))
    throw std::invalid_argument("buildBvh: depth cap " + std::to_string(maxDepth) +
                                " out of range for " + std::to_string(tris.size()) + " triangles");

  unsigned hw = std::thread::hardware_concurrency();
  int threads = static_cast<int>(std::clamp(hw, 1u, 64u));
  int parallelLevels = 0;
  while ((1 << (parallelLevels + 1)) <= threads) ++parallelLevels;

  const std::size_t n = tris.size();
  Bvh bvh;
  Box rootBox, rootC;
  {
    std::vector<PrimRef> prims(n);
    {
      std::vector<Box> partB(threads), partC(threads);
      std::vector<std::size_t> bad(threads, n);
      parallelChunks(n, unsigned(threads), kMinPrimsPerThread, [&](std::size_t slot, std::size_t b, std::size_t e) {
        Box box, cbox;
        for (std::size_t i = b; i < e; ++i) {
          const SceneTriangle& t = tris[i];
          PrimRef& p = prims[i];
          p.lo = glm::min(glm::min(t.v[0], t.v[1]), t.v[2]);
          p.hi = glm::max(glm::max(t.v[0], t.v[1]), t.v[2]);
          p.id = static_cast<std::uint32_t>(i);
          p.pad = 0;
          if (!(finite(t.v[0]) && finite(t.v[1]) && finite(t.v[2])) && bad[slot] == n)
            bad[slot] = i;
          box.grow(p.lo, p.hi);
          cbox.grow(p.centroid());
        }
        partB[slot] = box;
        partC[slot] = cbox;
      });
      for (int s = 0; s < threads; ++s) {
        if (bad[s] != n)
          throw std::invalid_argument("buildBvh: triangle " + std::to_string(bad[s]) +
                                      " has a non-finite vertex");
        rootBox.grow(partB[s]);
        rootC.grow(partC[s]);
      }
    }

    Builder builder{prims.data(), options.bins, options.maxLeafSize, options.traversalCost,
                    options.intersectCost, maxDepth};
    bvh.nodes.reserve(2 * n - 1);  // upper bound; untouched capacity costs no memory
    bvh.nodes.emplace_back();
    bvh.depth = builder.build(bvh.nodes, 0, 0, n, rootBox, rootC, 0, parallelLevels);

    bvh.order.resize(n);
    for (std::size_t i = 0; i < n; ++i) bvh.order[i] = prims[i].id;
  }  // prims freed before the output triangles are allocated
  if (bvh.nodes.capacity() > bvh.nodes.size() + bvh.nodes.size() / 4) bvh.nodes.shrink_to_fit();

  bvh.triangles.resize(n);
  parallelFor(n, unsigned(threads), kMinPrimsPerThread, [&](std::size_t i) {
    const SceneTriangle& t = tris[bvh.order[i]];
    Triangle& o = bvh.triangles[i];
    o.v0 = glm::vec4(t.v[0], as_float(t.material));
    o.e1 = glm::vec4(t.v[1] - t.v[0], as_float(bvh.order[i]));
    o.e2 = glm::vec4(t.v[2] - t.v[0], 0.0f);
  });

  auto halfArea = [](const BvhNode& b) {
    double dx = b.maxX - b.minX, dy = b.maxY - b.minY, dz = b.maxZ - b.minZ;
    return dx * dy + dy * dz + dz * dx;
  };
  double rootArea = halfArea(bvh.nodes[0]);
  double cost = 0.0;
  for (const BvhNode& node : bvh.nodes) {
    double rel = rootArea > 0.0 ? halfArea(node) / rootArea : 1.0;
    cost += node.triCount == 0 ? options.traversalCost * rel
                               : options.intersectCost * static_cast<double>(node.triCount) * rel;
  }
  bvh.sahCost = cost;
  collapseWide(bvh);
  bvh.buildMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return bvh;
}

}  // namespace montecl
