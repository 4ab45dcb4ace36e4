// gltf_placement_budget.h: the memory check of a glTF file's placements (its nodes' meshes and
// EXT_mesh_gpu_instancing copies) from their declared counts, before any placement's matrix is
// made. Each placement ends as an instance or, when its mesh emits, as a copy of the mesh's
// triangles: the cheaper of the two is the least it costs. Reads the model; writes nothing.
#pragma once
#include <tiny_gltf.h>

#include <cstdint>
#include <string>

namespace montecl {

class GltfPlacementBudget {
 public:
  // trianglesBefore: the scene's triangles before this file.
  GltfPlacementBudget(const tinygltf::Model& m, std::uint64_t trianglesBefore);
  // Node `node` places mesh `mesh` `count` times.
  void add(std::size_t node, std::size_t mesh, std::uint64_t count);
  // "" while the least all placements cost fits the memory check; else the refusal the loader
  // gives when it makes them ("gives N instances: ..." or, for a mesh that emits, "gives N
  // triangles: ..."), with the totals of the whole file, and in `node` the node where it was passed.
  std::string refusal(std::size_t& node) const;

 private:
  const tinygltf::Model& m_;
  std::uint64_t before_, instances_ = 0, copies_ = 0, leastBytes_ = 0;
  std::size_t overNode_ = 0;
  bool over_ = false, overEmits_ = false;
};

}  // namespace montecl
