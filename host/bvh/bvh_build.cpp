// bvh_build.cpp: binned-SAH BVH builder on the host, flattened depth-first into 32-byte BvhNodes
// (its parts: bvh_builder.h). This file: the entry point, the triangle references, the output
// triangles in leaf order and the SAH cost.
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
// node's, in powers of two; bvh_binning.cpp, bvh_size_classes.h); a node of at most 16 sorts its
// centroids on each axis and evaluates every object split (exact, and cheaper than binning at that
// size; bvh_sweep.cpp). A node with at most maxLeafSize (default 4,
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
// identical to the single-threaded build (bvh_flatten.cpp). The 8-wide collapse is not part of the
// build: Bvh::wideNodes() makes it on first use (bvh_wide.cpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "bvh/bvh.h"
#include "bvh/bvh_builder.h"
#include "bvh/bvh_internal.h"
#include "bvh/bvh_spatial.h"
#include "util/parallel_for.h"

namespace montecl {

using namespace bvhbuild;

namespace {

bool finiteVertex(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

BvhNode emptyBinaryNode() {
  const float inf = std::numeric_limits<float>::infinity();
  BvhNode n;
  n.minX = n.minY = n.minZ = inf;
  n.maxX = n.maxY = n.maxZ = -inf;
  n.leftFirst = 0;
  n.triCount = 0;
  return n;
}

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
  if (!(options.splitBudget >= 0.0f && options.splitBudget <= 4.0f) ||
      !(options.splitAlpha >= 0.0f && std::isfinite(options.splitAlpha)))
    throw std::invalid_argument("buildBvh: splitBudget must be in [0, 4] and splitAlpha finite and >= 0");
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
          if (!(finiteVertex(t.v[0]) && finiteVertex(t.v[1]) && finiteVertex(t.v[2])) && bad[slot] == n)
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

    if (options.splitBudget > 0.0f) {
      bvh.depth = buildSpatialTree(tris, options, maxDepth, std::move(prims), rootBox, rootC,
                                   parallelLevels, bvh.nodes, bvh.order);
    } else {
      Builder builder{prims.data(), options.bins, options.maxLeafSize, options.traversalCost,
                      options.intersectCost, maxDepth};
      bvh.nodes.reserve(2 * n - 1);  // upper bound; untouched capacity costs no memory
      bvh.nodes.emplace_back();
      bvh.depth = builder.build(bvh.nodes, 0, 0, n, rootBox, rootC, 0, parallelLevels);
      bvh.order.resize(n);
      for (std::size_t i = 0; i < n; ++i) bvh.order[i] = prims[i].id;
    }
  }  // prims freed before the output triangles are allocated
  if (bvh.nodes.capacity() > bvh.nodes.size() + bvh.nodes.size() / 4) bvh.nodes.shrink_to_fit();
  if (bvh.order.capacity() > bvh.order.size() + bvh.order.size() / 8) bvh.order.shrink_to_fit();
  if (bvh.order.size() >= (std::size_t(1) << 31))
    throw std::invalid_argument("buildBvh: more than 2^31 triangle references");

  // Canonical slot of each input triangle: the first leaf slot referencing it.
  const std::size_t m = bvh.order.size();
  std::vector<std::uint32_t> canonical(n, 0xffffffffu);
  for (std::size_t i = m; i-- > 0;) canonical[bvh.order[i]] = static_cast<std::uint32_t>(i);
  bvh.inputCount = n;
  bvh.triangles.resize(m);
  parallelFor(m, unsigned(threads), kMinPrimsPerThread, [&](std::size_t i) {
    const SceneTriangle& t = tris[bvh.order[i]];
    Triangle& o = bvh.triangles[i];
    o.v0 = glm::vec4(t.v[0], as_float(t.material));
    o.e1 = glm::vec4(t.v[1] - t.v[0], as_float(canonical[bvh.order[i]]));
    o.e2 = glm::vec4(t.v[2] - t.v[0], as_float(std::uint32_t(t.attributes)));
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
  bvh.buildMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return bvh;
}

}  // namespace montecl
