// stage_program.cpp: the layout rule and the stage program built for it (see stage_program.h).
#include "render/stage_program.h"

#include "cl/device_tuning.h"
#include "util/errors.h"

namespace montecl {

BvhLayout resolveStageLayout(BvhLayout requested, const DeviceInfo& device) {
  if (device.isHost) {
    if (requested == BvhLayout::Binary)
      throw InputError("--bvh-layout binary: the host backend traverses the wide BVH only");
    return BvhLayout::Wide;
  }
  return resolveBvhLayout(requested, device.isGpu);
}

std::string stageBuildOptions(BvhLayout resolved, unsigned lanes) {
  std::string options = resolved == BvhLayout::Binary ? "-DMCL_BVH_BINARY=1" : "";
  if (lanes > 1) options += (options.empty() ? "" : " ") + std::string("-DMCL_LANES=") + std::to_string(lanes);
  return options;
}

StageProgram::StageProgram(const DeviceInfo& device, BvhLayout layout, std::size_t workGroupSize,
                           bool profiling, unsigned lanes)
    : layout_(resolveStageLayout(layout, device)), lanes_(resolveLanes(lanes, device)),
      session_(device, workGroupSize, profiling, stageBuildOptions(layout_, lanes_)) {}

cl::Buffer StageProgram::uploadNodes(const Bvh& bvh) const {
  if (layout_ == BvhLayout::Binary)
    return session_.upload(bvh.nodes.empty() ? std::vector<BvhNode>{emptyBinaryNode()} : bvh.nodes);
  return session_.upload(bvh.wideNodes());  // never empty: an empty Bvh has one node of empty slots
}

}  // namespace montecl
