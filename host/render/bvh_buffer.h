// bvh_buffer.h: uploads the nodes of the BVH layout a session's kernels traverse (Bvh::wideNodes() or
// Bvh::nodes, ClSession::layout) into a read-only device buffer.
#pragma once
#include "bvh/bvh.h"
#include "cl/cl_session.h"

namespace montecl {

// An empty Bvh uploads one node that no ray enters.
cl::Buffer uploadBvhNodes(const ClSession& session, const Bvh& bvh);

}  // namespace montecl
