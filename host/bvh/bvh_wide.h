// bvh_wide.h: the 8-wide layout (WideNode, MCL_WIDE_WIDTH children per node) is not built: it is
// converted from the canonical binary tree when first asked for (tinybvh's ConvertFrom style),
// through Bvh::wideNodes(), so a run of the binary layout never makes it.
#pragma once
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include "kernels/shared/types.h"

namespace montecl {

// Collapses a binary tree (Bvh::nodes over triangleCount triangles) into MCL_WIDE_WIDTH-wide
// nodes: each wide node takes the binary node's two children and, while it has fewer than
// MCL_WIDE_WIDTH, replaces its interior child of largest surface area * sqrt(triangle references
// below it) by that child's two children. Wide nodes are laid out depth-first (element 0 the root); leaves keep their triangle
// ranges. Empty nodes give one node of empty slots. Throws std::invalid_argument above 2^27
// triangles (the leaf encoding's limit).
std::vector<WideNode> collapseWide(const std::vector<BvhNode>& nodes, std::size_t triangleCount);

// A wide node whose slots are all empty (no ray enters them): the whole tree of an empty Bvh.
WideNode emptyWideNode();

// The collapse behind Bvh::wideNodes(): made once, by the first caller, whichever thread it is on.
// A copy starts empty (its nodes may change before it is first asked), a move keeps it.
class WideCache {
 public:
  WideCache() = default;
  WideCache(const WideCache&) {}
  WideCache& operator=(const WideCache&) {
    state_ = std::make_unique<State>();
    return *this;
  }
  WideCache(WideCache&&) noexcept = default;
  WideCache& operator=(WideCache&&) noexcept = default;

  const std::vector<WideNode>& get(const std::vector<BvhNode>& nodes, std::size_t triangleCount) const;
  // Holds wide as the collapse (for a tree that has no binary form, e.g. the two-level BVH's).
  void preset(std::vector<WideNode> wide);

 private:
  struct State {
    std::once_flag once;
    std::vector<WideNode> wide;
  };
  std::unique_ptr<State> state_ = std::make_unique<State>();
};

}  // namespace montecl
