// bvh.h: binned-SAH BVH over a triangle soup, flattened depth-first into 32-byte BvhNodes, its
// 8-wide form made on demand (bvh_wide.h), and the host reference traversal (the same code the
// kernels run, from kernels/shared/traverse.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bvh/bvh_layout.h"
#include "bvh/bvh_wide.h"
#include "kernels/shared/types.h"
#include "scene/scene.h"

struct AlphaScene;  // kernels/shared/surface_texture.h

namespace montecl {

struct BvhBuildOptions {
  int bins = 32;            // SAH bins per axis
  int maxLeafSize = 4;      // a node with at most this many triangles may become a leaf
  float traversalCost = 1.0f;
  float intersectCost = 0.5f;  // per triangle; below traversalCost: leaves are tested 4 at a time
  // Spatial splits (SBVH, bvh_spatial.h): at most splitBudget extra triangle references per input
  // triangle (0: none, the plain object-split build); a node tries them only where its best
  // object split's children overlap by more than splitAlpha of the root's surface area.
  float splitBudget = 0.3f;
  float splitAlpha = 1e-3f;
};

struct Bvh {
  std::vector<BvhNode> nodes;         // nodes[0] is the root; children of an interior node are adjacent
  // In leaf order, ready for the device. With spatial splits a triangle can be referenced by
  // several leaves: each reference is a full copy, and e1.w holds the canonical slot (the first
  // slot holding that input triangle), which closest hit returns as Hit::tri.
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> order;   // triangles[i] came from input triangle order[i]
  std::size_t inputCount = 0;         // input triangles (triangles.size() minus the duplicates)
  int depth = 0;                      // longest root-to-leaf path (always < MCL_BVH_STACK_SIZE)
  double sahCost = 0.0;               // SAH cost of the tree (traversalCost/intersectCost weighted)
  double buildMs = 0.0;               // of the binary tree (the wide collapse is not built here)
  // Non-empty: a two-level BVH (bvh_instances.h buildSceneBvh): wideNodes() holds the top level
  // and the bottom levels, triangles are in their meshes' object spaces, these the placements
  // (leaf order); nodes is one empty binary node (the binary layout has no two-level form).
  std::vector<Instance> instances;

  // The same tree collapsed 8-wide (collapseWide, element 0 the root): what the wide layout
  // traverses. Collapsed on the first call (thread-safe) and kept; never empty. Do not change
  // nodes after the first call. Throws std::invalid_argument above 2^27 triangles.
  const std::vector<WideNode>& wideNodes() const;

  WideCache wideCache;                // behind wideNodes()
};

Bvh buildBvh(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options = {});

// A binary node with an empty box (no ray enters it): the whole binary tree of an empty Bvh.
BvhNode emptyBinaryNode();

// Reference traversal on the host, of the given layout (Auto: wide). Both layouts give the same
// hit distance; the triangle can differ only where two triangles tie at that distance. With
// alpha, hits on flagged cut-out triangles (MCL_ATTR_ALPHA) exist only where the alpha test passes.
Hit intersectClosest(const Bvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                     BvhLayout layout = BvhLayout::Wide, const AlphaScene* alpha = nullptr);
bool intersectAny(const Bvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                  BvhLayout layout = BvhLayout::Wide, const AlphaScene* alpha = nullptr);

}  // namespace montecl
