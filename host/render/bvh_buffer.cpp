// bvh_buffer.cpp: the node buffer of the session's BVH layout (see bvh_buffer.h).
#include "render/bvh_buffer.h"

namespace montecl {

cl::Buffer uploadBvhNodes(const ClSession& session, const Bvh& bvh) {
  if (session.layout() == BvhLayout::Binary)
    return session.upload(bvh.nodes.empty() ? std::vector<BvhNode>{emptyBinaryNode()} : bvh.nodes);
  return session.upload(bvh.wideNodes());  // never empty
}

}  // namespace montecl
