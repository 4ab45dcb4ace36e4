// gltf_instancing.h: a glTF node's EXT_mesh_gpu_instancing (TRANSLATION / ROTATION / SCALE
// accessors, one element per instance) as one local matrix per instance, which the loader puts
// before the node's world matrix as the extension says. Reads the model only; bad accessors are
// InputError naming the attribute's key.
#pragma once
#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace montecl {

struct GltfInstances {
  bool present = false;    // the node has the extension; else one instance, the identity
  std::size_t count = 1;   // instances (every attribute's accessor count)
  std::vector<float> t, r, s;  // xyz, xyzw (unit or normalised here), xyz per instance; empty: default
  std::vector<std::string> ignored;  // attributes montecl does not read (custom _ID and the like)
  // Instance k's matrix: translate(t) * rotate(r) * scale(s), as a node's TRS.
  glm::dmat4 local(std::size_t k) const;
};

// The node's instances; where is "nodes[i]" (messages name where + ".extensions.EXT_mesh_gpu_instancing...").
GltfInstances gltfNodeInstances(const std::string& file, const tinygltf::Model& m, const tinygltf::Node& node,
                                const std::string& where);

}  // namespace montecl
