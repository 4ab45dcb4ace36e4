// bvh_instances.h: the two-level BVH of instanced geometry: one bottom-level BVH per unique mesh
// over its own (object-space) triangles and a top level over the instances' world boxes, all in
// one wide node array and one triangle array (kernels/shared/traverse_instances.h traverses it),
// so memory grows with the unique geometry, not with the copies; and the host reference traversal.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"

namespace montecl {

// One placement of meshes[mesh] (column vectors, p_world = objectToWorld * p_object).
struct BvhInstanceDesc {
  std::uint32_t mesh = 0;
  glm::mat4 objectToWorld{1.0f};
};

struct TwoLevelBvh {
  std::vector<WideNode> nodes;          // the top level's root at 0, then each mesh's bottom level
  std::vector<Triangle> triangles;      // every mesh's triangles, bottom level by bottom level (object space)
  std::vector<Instance> instances;      // in the top level's leaf order (Instance::id: the input index)
  std::vector<std::uint32_t> meshRoot;     // per mesh: its bottom level's root in nodes
  std::vector<std::uint32_t> meshTriBase;  // per mesh: its first triangle in triangles
  std::vector<std::uint32_t> meshTriCount; // per mesh: its triangles (slots) in triangles
  std::vector<std::uint32_t> triangleSource;  // triangles[i] came from triangle triangleSource[i] of its mesh
  int depth = 0;                        // top level's depth plus the deepest bottom level's
  std::size_t bytes() const;            // of nodes, triangles and instances (what the device holds)
};

// Builds the bottom levels (options as for buildBvh) and the top level (object splits, one
// instance per leaf). Instances of meshes without triangles are left out. Throws
// std::invalid_argument on a mesh index out of range, a transform that is not invertible or not
// finite, or more than 2^27 triangles or instances.
TwoLevelBvh buildTwoLevelBvh(const std::vector<std::vector<SceneTriangle>>& meshes,
                             const std::vector<BvhInstanceDesc>& instances, const BvhBuildOptions& options = {});

// The two-level BVH as a Bvh for the code that indexes per-triangle arrays in BVH order (triangle
// shading, vertex colours, alpha flags, emitters): triangles and wideNodes() are the two-level
// ones, order[i] the scene triangle of slot i (meshFirstTri[mesh] + its index within the mesh).
// nodes is one empty binary node: the binary layout has no two-level form (refuse it).
Bvh sceneView(const TwoLevelBvh& bvh, const std::vector<std::uint32_t>& meshFirstTri);

// The BVH a render of scene traverses: buildBvh(scene.triangles) for a scene without instances
// (the same tree as ever); else the two-level BVH as sceneView gives it, with Bvh::instances set:
// mesh 0 the world-space triangles (outside every mesh range) placed once by the identity, meshes
// 1.. the scene's mesh ranges placed by Scene::instances. order[] maps slots to scene triangles.
// Throws std::invalid_argument as buildTwoLevelBvh.
Bvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options = {});

// Host reference traversal (the kernels' code): closest hit with the input index of the instance
// hit (MCL_NO_INSTANCE on a miss; hit.tri a slot of triangles), and any hit.
struct TwoLevelHit {
  Hit hit;
  std::uint32_t instance;
};
TwoLevelHit intersectClosest(const TwoLevelBvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                             const AlphaScene* alpha = nullptr);
bool intersectAny(const TwoLevelBvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                  const AlphaScene* alpha = nullptr);

}  // namespace montecl
