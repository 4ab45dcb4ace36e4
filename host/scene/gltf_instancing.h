// gltf_instancing.h: how a glTF node places its mesh: its local matrix and its
// EXT_mesh_gpu_instancing (TRANSLATION / ROTATION / SCALE accessors, one element per instance) as
// one local matrix per instance, which the loader puts before the node's world matrix as the
// extension says; the hierarchy's root nodes; and a mesh's declared triangle count (for the memory check). Reads the model only; bad accessors are
// InputError naming the attribute's key.
#pragma once
#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <cstdint>
#include <optional>
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

// A node's local matrix (its matrix, or translation x rotation x scale); a projective matrix, a
// matrix of other than 16 numbers or a zero quaternion is InputError naming where + the key.
glm::dmat4 gltfLocalTransform(const std::string& file, const tinygltf::Node& n, const std::string& where);

// Which of the file's scenes[] gltfRootNodes walks: `chosen` (the command line's --scene) when
// given, else the file's "scene", else 0. Throws InputError "--scene: scene N out of range: <file>
// has K scenes ..." for a chosen index the file does not have (a file without scenes[] has none).
std::size_t gltfSceneIndex(const std::string& file, const tinygltf::Model& m, std::optional<unsigned> chosen);

// The hierarchy's roots: scene `scene`'s nodes (gltfSceneIndex); every parentless node when the
// file has no scenes[].
std::vector<int> gltfRootNodes(const tinygltf::Model& m, std::size_t scene);

// The triangles a mesh declares (index or POSITION counts / 3), before any is read.
std::uint64_t gltfMeshTriangles(const tinygltf::Model& m, const tinygltf::Mesh& mesh);

}  // namespace montecl
