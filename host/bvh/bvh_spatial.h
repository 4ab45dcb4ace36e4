// bvh_spatial.h: spatial splits for the builder (SBVH: Stich, Friedrich and Dietrich, "Spatial
// splits in bounding volume hierarchies", HPG 2009). Where a node's best object split leaves its
// two children overlapping, a plane can instead cut the triangles that straddle it: each one is
// then referenced by both children, with its part on each side boxed separately (the triangle
// clipped to the plane, so both boxes are tighter). Used by bvh_sbvh.cpp; reads triangles and
// references, writes references.
#pragma once
#include <cstddef>
#include <vector>

#include "bvh/bvh_builder.h"

namespace montecl {
namespace bvhbuild {

// True when r's box is not empty (lo <= hi on every axis).
inline bool validRef(const PrimRef& r) {
  return r.lo.x <= r.hi.x && r.lo.y <= r.hi.y && r.lo.z <= r.hi.z;
}

// Splits reference r of triangle t at the plane `axis` = pos: left and right get the boxes of
// the triangle's parts below and above the plane, each intersected with r's box (so never outside
// it, nor outside t's box), and r's id. The edge crossings are widened by a few ulps off the
// axis, so both boxes together cover the part of t inside r's box despite rounding. A side the
// triangle does not reach gets an empty box (validRef false).
void splitReference(const PrimRef& r, const SceneTriangle& t, int axis, float pos, PrimRef& left,
                    PrimRef& right);

struct SpatialSplit {
  int axis = -1;   // -1: none
  int plane = 0;   // between bin `plane` and `plane + 1`
  float cost = 0.0f;
};

// Spatial binning of a node: `bins` equal slabs along each axis of the node's box; plane k sits
// between slab k and k+1 (k < bins - 1). A reference spans the slabs from the number of planes
// at or below its lo to the number of planes below its hi, so "left of plane k" (hi <= plane)
// and "right of plane k" (lo >= plane) mean the same in the binning and in the partition.
struct SpatialBinner {
  const SceneTriangle* tris;
  int bins;

  float planePos(const Box& bounds, int axis, int k) const;
  // Best spatial split of refs[0, n) in a node with box `bounds` (SAH with costs ct and ci);
  // axis -1 when no plane leaves references on both sides.
  SpatialSplit find(const PrimRef* refs, std::size_t n, const Box& bounds, float ct, float ci) const;
  // Distributes refs over the two sides of the split: whole when on one side, split in two
  // (splitReference) when straddling the plane, a part with an empty box dropped.
  void partition(const std::vector<PrimRef>& refs, const Box& bounds, const SpatialSplit& s,
                 std::vector<PrimRef>& left, std::vector<PrimRef>& right) const;
};

// The whole tree with spatial splits (bvh_sbvh.cpp): nodes as buildBvh lays them out, order the
// input triangle of each leaf slot (a triangle may fill several). Returns the depth.
int buildSpatialTree(const std::vector<SceneTriangle>& tris, const BvhBuildOptions& options,
                     int maxDepth, std::vector<PrimRef> prims, const Box& rootBox, const Box& rootC,
                     int parallelLevels, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& order);

}  // namespace bvhbuild
}  // namespace montecl
