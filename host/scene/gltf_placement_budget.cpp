// gltf_placement_budget.cpp: a glTF file's placements against the memory check before they are
// made (gltf_placement_budget.h). Reads the model; writes nothing.
#include "scene/gltf_placement_budget.h"

#include <algorithm>

#include "scene/gltf_instancing.h"
#include "scene/scene_instances.h"
#include "util/host_memory.h"

namespace montecl {
namespace {

// Whether a primitive's material has an emissive factor or texture: its placements become copies
// (the emitter table is world space). A strength of 0 may still make it dark: the check takes the
// cheaper outcome, so the guess only picks the message.
bool meshMayEmit(const tinygltf::Model& m, const tinygltf::Mesh& mesh) {
  for (const tinygltf::Primitive& p : mesh.primitives) {
    if (p.material < 0 || static_cast<std::size_t>(p.material) >= m.materials.size()) continue;
    const tinygltf::Material& g = m.materials[static_cast<std::size_t>(p.material)];
    if (g.emissiveTexture.index >= 0) return true;
    for (double f : g.emissiveFactor)
      if (f > 0.0) return true;
  }
  return false;
}

constexpr std::uint64_t kCap = std::uint64_t(1) << 40;  // counts past it are refused anyway: no wrap

}  // namespace

GltfPlacementBudget::GltfPlacementBudget(const tinygltf::Model& m, std::uint64_t trianglesBefore)
    : m_(m), before_(trianglesBefore) {}

void GltfPlacementBudget::add(std::size_t node, std::size_t mesh, std::uint64_t count) {
  const tinygltf::Mesh& g = m_.meshes[mesh];
  const std::uint64_t tris = std::min(gltfMeshTriangles(m_, g), kCap);
  count = std::min(count, kCap);
  const bool emits = meshMayEmit(m_, g);
  (emits ? copies_ : instances_) += emits ? (count != 0 && tris > kCap / count ? kCap : tris * count) : count;
  copies_ = std::min(copies_, kCap), instances_ = std::min(instances_, kCap);
  const std::uint64_t copyBytes = tris * (sizeof(SceneTriangle) + 125);
  leastBytes_ = std::min(leastBytes_ + count * std::min(instanceBytes(), copyBytes), kCap * 1024);
  if (!over_ && leastBytes_ > hostMemoryBytes()) over_ = true, overNode_ = node, overEmits_ = emits;
}

std::string GltfPlacementBudget::refusal(std::size_t& node) const {
  if (!over_) return "";
  node = overNode_;
  std::string r = overEmits_ ? sceneMemoryRefusal(before_ + copies_, sizeof(SceneTriangle))
                             : instanceMemoryRefusal(instances_);
  if (r.empty())  // the guess's own count fits: the placements together do not
    r = "gives " + std::to_string(instances_) + " instances and " + std::to_string(copies_) +
        " copied triangles: needs at least " + gibText(leastBytes_) + " of memory, this machine has " +
        gibText(hostMemoryBytes());
  return r;
}

}  // namespace montecl
