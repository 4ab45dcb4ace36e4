// gltf_instancing.cpp: reads EXT_mesh_gpu_instancing of a glTF node and the hierarchy's roots
// (gltf_instancing.h).
#include "scene/gltf_instancing.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/gltf_model.h"
#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {

glm::dmat4 GltfInstances::local(std::size_t k) const {
  if (!present) return glm::dmat4(1.0);
  // Every part given (defaults where an attribute is absent), in the order a node's TRS is built,
  // so an instance and a node with the same translation, rotation and scale get the same bits.
  glm::dvec3 tv(0.0), sv(1.0);
  glm::dquat q(1.0, 0.0, 0.0, 0.0);
  if (!t.empty()) tv = glm::dvec3(t[3 * k], t[3 * k + 1], t[3 * k + 2]);
  if (!r.empty()) q = glm::dquat(r[4 * k + 3], r[4 * k], r[4 * k + 1], r[4 * k + 2]);  // glTF: x y z w
  if (!s.empty()) sv = glm::dvec3(s[3 * k], s[3 * k + 1], s[3 * k + 2]);
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), tv);
  m = m * glm::mat4_cast(glm::normalize(q));
  return glm::scale(m, sv);
}

glm::dmat4 gltfLocalTransform(const std::string& file, const tinygltf::Node& n, const std::string& where) {
  if (n.matrix.size() == 16) {
    glm::dmat4 t;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) t[c][r] = n.matrix[std::size_t(4 * c + r)];  // column-major, as glm
    // glTF node matrices are affine; a projective one would put vertices through a division.
    if (t[0][3] != 0.0 || t[1][3] != 0.0 || t[2][3] != 0.0 || t[3][3] != 1.0)
      loadFail(file, where + ".matrix", "last row must be 0 0 0 1 (an affine transform; this one is projective)");
    return t;
  }
  if (!n.matrix.empty()) loadFail(file, where + ".matrix", "expected 16 numbers");
  glm::dmat4 t(1.0);
  if (n.translation.size() == 3) t = glm::translate(t, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // glTF: x y z w
    if (glm::length(q) == 0.0) loadFail(file, where + ".rotation", "zero quaternion");
    t = t * glm::mat4_cast(glm::normalize(q));
  }
  if (n.scale.size() == 3) t = glm::scale(t, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return t;
}

// The triangles a mesh declares (index or POSITION counts / 3), before any is read.
std::uint64_t gltfMeshTriangles(const tinygltf::Model& m, const tinygltf::Mesh& mesh) {
  std::uint64_t n = 0;
  for (const tinygltf::Primitive& p : mesh.primitives) {
    auto it = p.attributes.find("POSITION");
    const int a = p.indices >= 0 ? p.indices : it == p.attributes.end() ? -1 : it->second;
    if (a < 0 || static_cast<std::size_t>(a) >= m.accessors.size()) continue;
    const std::uint64_t count = m.accessors[std::size_t(a)].count;
    if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) n += count / 3;
    else if ((p.mode == TINYGLTF_MODE_TRIANGLE_STRIP || p.mode == TINYGLTF_MODE_TRIANGLE_FAN) && count >= 3) n += count - 2;
  }
  return n;
}

GltfInstances gltfNodeInstances(const std::string& file, const tinygltf::Model& m, const tinygltf::Node& node,
                                const std::string& where) {
  GltfInstances out;
  const auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
  if (ext == node.extensions.end()) return out;
  out.present = true;
  const std::string base = where + ".extensions.EXT_mesh_gpu_instancing";
  if (!ext->second.IsObject() || !ext->second.Has("attributes") || !ext->second.Get("attributes").IsObject())
    loadFail(file, base + ".attributes", "expected an object of accessor indices");
  const tinygltf::Value& attrs = ext->second.Get("attributes");
  bool first = true;
  for (const std::string& name : attrs.Keys()) {
    const std::string key = base + ".attributes." + oneLine(name, 40);
    const bool known = name == "TRANSLATION" || name == "ROTATION" || name == "SCALE";
    if (!known) {
      out.ignored.push_back(name);
      continue;
    }
    const tinygltf::Value& v = attrs.Get(name);
    if (!v.IsInt() || v.GetNumberAsInt() < 0) loadFail(file, key, "expected an accessor index");
    const int index = v.GetNumberAsInt();
    if (static_cast<std::size_t>(index) >= m.accessors.size())
      loadFail(file, key, "accessor index " + std::to_string(index) + " out of range");
    const std::size_t count = m.accessors[std::size_t(index)].count;
    if (!first && count != out.count)
      loadFail(file, key, "has " + std::to_string(count) + " elements, another attribute " + std::to_string(out.count) +
                              " (every attribute needs one element per instance)");
    out.count = count;
    first = false;
    // ROTATION: unit quaternions, FLOAT or normalized signed byte / short (as NORMAL allows);
    // TRANSLATION and SCALE: FLOAT, or the integer types KHR_mesh_quantization lists (as POSITION).
    if (name == "ROTATION") {
      out.r = readFloatAccessor(file, m, index, 4, key, AccessorUse::Normal);
      for (std::size_t k = 0; k < count; ++k)
        if (out.r[4 * k] == 0.0f && out.r[4 * k + 1] == 0.0f && out.r[4 * k + 2] == 0.0f && out.r[4 * k + 3] == 0.0f)
          loadFail(file, key, "element " + std::to_string(k) + " is a zero quaternion");
    } else {
      (name == "TRANSLATION" ? out.t : out.s) = readFloatAccessor(file, m, index, 3, key, AccessorUse::Position);
    }
  }
  if (first) loadFail(file, base + ".attributes", "none of TRANSLATION, ROTATION, SCALE given");
  return out;
}

std::size_t gltfSceneIndex(const std::string& file, const tinygltf::Model& m, std::optional<unsigned> chosen) {
  const std::size_t n = m.scenes.size();
  if (chosen && *chosen >= n)
    throwInputError("--scene", "",
                    "scene " + std::to_string(*chosen) + " out of range: " + oneLine(file) + " has " +
                        (n == 0 ? std::string("no scenes[] (every root node is rendered; leave --scene out)")
                                : std::to_string(n) + (n == 1 ? " scene" : " scenes") + " (from 0)"));
  if (chosen) return *chosen;
  return m.defaultScene >= 0 && static_cast<std::size_t>(m.defaultScene) < n ? std::size_t(m.defaultScene) : 0;
}

std::vector<int> gltfRootNodes(const tinygltf::Model& m, std::size_t scene) {
  if (scene < m.scenes.size()) return m.scenes[scene].nodes;
  std::vector<bool> child(m.nodes.size(), false);
  for (const tinygltf::Node& n : m.nodes)
    for (int c : n.children)
      if (c >= 0 && static_cast<std::size_t>(c) < m.nodes.size()) child[std::size_t(c)] = true;
  std::vector<int> roots;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (!child[i]) roots.push_back(static_cast<int>(i));
  return roots;
}

}  // namespace montecl
