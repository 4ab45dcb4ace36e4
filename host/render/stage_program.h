// stage_program.h: montecl's stage kernels (kernels/montecl.cl) built for one BVH layout on one
// device, and the layout rule, once: which layout a device's stages traverse (the host backend:
// wide only), the build option that selects it, and the node buffer it reads.
#pragma once
#include <string>

#include "bvh/bvh.h"
#include "cl/cl_session.h"

namespace montecl {

// The layout the stages of `device` traverse: Auto -> binary on GPUs, wide otherwise; the host
// backend (device.isHost) runs wide only (Auto and Wide give Wide; Binary is bad input).
BvhLayout resolveStageLayout(BvhLayout requested, const DeviceInfo& device);
// The build options that select a resolved layout's traversal (kernels/shared/traverse.h).
// plus -DMCL_LANES=W for the packet stages (kernels/shared/lanes.h), so the program cache keys on W.
std::string stageBuildOptions(BvhLayout resolved, unsigned lanes = 1);

class StageProgram {
 public:
  // Builds montecl.cl for resolveStageLayout(layout, device) (device must not be the host).
  explicit StageProgram(const DeviceInfo& device, BvhLayout layout = BvhLayout::Auto,
                        std::size_t workGroupSize = 0, bool profiling = false, unsigned lanes = 0);
  ClSession& session() { return session_; }
  const ClSession& session() const { return session_; }
  BvhLayout layout() const { return layout_; }  // resolved: Wide or Binary
  unsigned lanes() const { return lanes_; }      // resolved packet width W (resolveLanes)
  // The node array of the layout, as a read-only buffer; an empty Bvh uploads one node that no ray enters.
  cl::Buffer uploadNodes(const Bvh& bvh) const;

 private:
  BvhLayout layout_;
  unsigned lanes_;
  ClSession session_;
};

}  // namespace montecl
