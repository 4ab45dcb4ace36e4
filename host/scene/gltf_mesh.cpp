// gltf_mesh.cpp: loadGltfInto(): a glTF 2.0 scene (gltf_model.h) into a Scene. Walks the chosen
// scene's node hierarchy (--scene N, else the file's default; TRS or matrix transforms);
// TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (indexed or not) give triangles with
// POSITION, NORMAL (kHasNormals), TANGENT (kHasTangents, Scene::vertexTangents, placed by
// Placement::tangent), COLOR_0 and the TEXCOORD_n set the material's textures read (kHasUv, v
// flipped to OBJ's convention: v = 1 - v_gltf). Materials: gltf_material.h, made on first use.
// EXT_mesh_gpu_instancing: one copy of the node's mesh per instance (flattened, or a mesh range
// placed many times). KHR_draco_mesh_compression: a primitive's attributes and indices come from its
// Draco buffer (gltf_draco.h), decoded once however many nodes use the mesh, and are read as if
// they were accessors. The first perspective camera met in the hierarchy is returned. Everything
// else the file uses is one warning per kind.
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "util/host_memory.h"
#include "scene/gltf_accessor_cache.h"
#include "scene/gltf_draco.h"
#include "scene/gltf_instancing.h"
#include "scene/gltf_lights.h"
#include "scene/gltf_material.h"
#include "scene/gltf_model.h"
#include "scene/gltf_placement_budget.h"
#include "scene/gltf_texture_info.h"
#include "scene/load_util.h"
#include "scene/mesh_entry.h"
#include "scene/mesh_loaders.h"
#include "scene/scene_instances.h"

namespace montecl {
namespace {

using tinygltf::Model;

struct Loader {
  const std::string& file;
  const Model& m;
  Scene& scene;
  KindWarnings unused;
  GltfMaterials materials{file, m, scene, unused};  // glTF material -> scene material, made on first use
  std::vector<Camera> cameras{};  // every perspective camera, in the order met (the first is the camera)
  std::size_t skippedPrimitives = 0;  // points and lines: named when nothing else is left
  std::map<const tinygltf::Primitive*, GltfDracoMesh> draco{};  // decoded Draco primitives
  GltfAccessorCache accessors{};  // primitives sharing an accessor decode it once

  void primitive(const tinygltf::Primitive& p, const glm::dmat4& world, const std::string& where);
  void takeCamera(int index, const glm::dmat4& world, const std::string& where);
};

std::string itemWhere(const char* kind, std::size_t i) { return std::string(kind) + "[" + std::to_string(i) + "]"; }

void Loader::primitive(const tinygltf::Primitive& p, const glm::dmat4& world, const std::string& where) {
  const int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    const std::string n = std::to_string(p.mode);
    unused.add("mode " + n, where, "primitive mode " + n + " (points or lines, not triangles) skipped");
    return void(++skippedPrimitives);
  }
  auto attr = [&](const char* name) {
    auto it = p.attributes.find(name);
    return it == p.attributes.end() ? -1 : it->second;
  };
  // Texture coordinate sets other than the one the material's textures read change nothing.
  for (const auto& a : p.attributes)
    if (a.first != "POSITION" && a.first != "NORMAL" && a.first != "COLOR_0" && a.first != "TANGENT" &&
        a.first.compare(0, 9, "TEXCOORD_") != 0)
      unused.add("attribute " + a.first, where, "attribute " + oneLine(a.first, 40) + " not used by montecl, ignored");
  if (!p.targets.empty()) unused.add("morph", where, "morph targets not used by montecl (the base mesh is rendered)");
  if (attr("POSITION") < 0) loadFail(file, where, "primitive without POSITION");
  const GltfDracoMesh* dm = nullptr;  // the decoded Draco buffer, when the primitive has one
  if (hasGltfDraco(p)) {
    auto it = draco.find(&p);
    if (it == draco.end()) it = draco.emplace(&p, decodeGltfDraco(file, m, p, where)).first;
    dm = &it->second;
  }
  // An attribute's values: decoded from the Draco buffer when it holds it (the accessor, checked
  // alike, gives only its type), else read from its accessor.
  const auto values = [&](const std::string& name, int components, AccessorUse use) -> const std::vector<float>& {
    const std::string key = where + "." + name;
    if (dm && dm->attributes.count(name)) {
      checkFloatAccessor(file, m, attr(name.c_str()), components, key, use);
      return dm->attributes.at(name);
    }
    return accessors.floats(name, file, m, attr(name.c_str()), components, key, use);
  };
  static const std::vector<float> kNone;
  const std::vector<float>& pos = values("POSITION", 3, AccessorUse::Position);
  const std::size_t n = pos.size() / 3;
  const std::vector<float>& nor = attr("NORMAL") >= 0 ? values("NORMAL", 3, AccessorUse::Normal) : kNone;
  const std::uint32_t mat = materials.index(p.material);
  const int set = materials.uvSet(p.material);
  const std::string uvName = "TEXCOORD_" + std::to_string(set);
  if (set > 0 && attr(uvName.c_str()) < 0)  // TEXCOORD_0 missing: no UVs, as always
    loadFail(file, materials.uvSetKey(p.material), "names " + uvName + ", which " + where + " does not have");
  const std::vector<float>& uv = attr(uvName.c_str()) >= 0 ? values(uvName, 2, AccessorUse::TexCoord) : kNone;
  // COLOR_0 (VEC3 or VEC4: alpha not read) multiplies the base colour.
  const int colA = attr("COLOR_0");
  const int colN = colA >= 0 && std::size_t(colA) < m.accessors.size() && m.accessors[std::size_t(colA)].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
  const std::vector<float>& col = colA >= 0 ? values("COLOR_0", colN, AccessorUse::Any) : kNone;
  if (colA >= 0 && col.size() / std::size_t(colN) != n) loadFail(file, where, "attributes have different counts");
  if ((!nor.empty() && nor.size() / 3 != n) || (!uv.empty() && uv.size() / 2 != n))
    loadFail(file, where, "attributes have different counts");
  // TANGENT (VEC4: xyz the tangent, w the handedness; FLOAT or, quantized, as NORMAL) gives normal
  // maps the file's tangent frame (normal_map.h); without it the frame comes from the UVs.
  const std::vector<float>& tan = attr("TANGENT") >= 0 ? values("TANGENT", 4, AccessorUse::Normal) : kNone;
  if (!tan.empty() && tan.size() / 4 != n)
    loadFail(file, where + ".TANGENT", std::to_string(tan.size() / 4) + " elements, POSITION has " + std::to_string(n));
  const bool indexed = p.indices >= 0 || dm;  // a Draco mesh's faces index its points
  static const std::vector<std::uint32_t> kNoIndices;
  const std::vector<std::uint32_t>& idx =
      dm ? dm->indices : p.indices >= 0 ? accessors.indices(file, m, p.indices, where + ".indices") : kNoIndices;
  const std::size_t count = indexed ? idx.size() : n;  // the primitive's vertices, in order
  if (mode == TINYGLTF_MODE_TRIANGLES && count % 3 != 0)
    loadFail(file, where, std::to_string(count) + " vertices do not make whole triangles");
  const std::size_t corners = mode == TINYGLTF_MODE_TRIANGLES ? count : 3 * (count >= 3 ? count - 2 : 0);
  // Corner k of triangle i, as the glTF specification orders strips (every other one flipped, so
  // all keep the first one's winding) and fans (v[i+1], v[i+2], v[0]).
  const auto cornerOf = [mode](std::size_t c) {
    const std::size_t i = c / 3, k = c % 3;
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) return k == 0 ? i : k == 1 ? i + 1 + i % 2 : i + 2 - i % 2;
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) return k == 2 ? std::size_t(0) : i + k + 1;
    return c;
  };
  const Placement placement(world);  // its normal matrix, mirror flag and tangent rule
  for (std::size_t c = 0; c < corners; c += 3) {
    SceneTriangle t{};
    glm::vec3 colour[3];
    glm::vec4 tangent[3];
    bool normals = !nor.empty(), tangents = !tan.empty();
    for (int k = 0; k < 3; ++k) {
      const std::size_t j = cornerOf(c + std::size_t(k));
      const std::size_t v = indexed ? idx[j] : j;
      if (v >= n) loadFail(file, where + ".indices", "index " + std::to_string(v) + " out of range (" + std::to_string(n) + " vertices)");
      const int kk = placement.mirror && k > 0 ? 3 - k : k;  // a mirroring transform swaps corners 1 and 2
      t.v[kk] = glm::vec3(world * glm::dvec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0));
      if (!tan.empty()) {  // w: the handedness's sign, +1 or -1 exactly
        tangent[kk] = placement.tangent(glm::vec4(tan[4 * v], tan[4 * v + 1], tan[4 * v + 2], tan[4 * v + 3] < 0.0f ? -1.0f : 1.0f));
        tangents = tangents && glm::vec3(tangent[kk]) != glm::vec3(0.0f);  // else the UVs' frame
      }
      if (!nor.empty()) {
        const glm::dvec3 nn = placement.normalMatrix * glm::dvec3(nor[3 * v], nor[3 * v + 1], nor[3 * v + 2]);
        const double len = glm::length(nn);
        normals = normals && len > 0.0 && std::isfinite(len);
        t.n[kk] = normals ? glm::vec3(nn / len) : glm::vec3(0.0f);
      }
      if (!uv.empty()) t.uv[kk] = glm::vec2(uv[2 * v], 1.0f - uv[2 * v + 1]);
      if (!col.empty())
        colour[kk] = glm::max(glm::vec3(col[colN * v], col[colN * v + 1], col[colN * v + 2]), glm::vec3(0.0f));
    }
    if (!normals)
      for (glm::vec3& x : t.n) x = glm::vec3(0.0f);
    t.attributes = static_cast<std::uint8_t>((normals ? kHasNormals : 0) | (uv.empty() ? 0 : kHasUv) |
                                             (col.empty() ? 0 : kHasColor) | (tangents ? kHasTangents : 0));
    t.material = mat;
    for (const glm::vec3& x : t.v)
      if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
        loadFail(file, where, "a node transform moves vertices out of float range");
    if (appendTriangle(scene, t))  // colours and tangents by triangle index
      appendCorners(scene, scene.triangles.size() - 1, col.empty() ? nullptr : colour, tangents ? tangent : nullptr);
  }
}

void Loader::takeCamera(int index, const glm::dmat4& world, const std::string& where) {
  // An index past the cameras was ignored: the render then framed the model itself, unasked.
  if (index < 0 || static_cast<std::size_t>(index) >= m.cameras.size())
    loadFail(file, where, "camera index " + std::to_string(index) + " out of range (" + std::to_string(m.cameras.size()) + " cameras)");
  const tinygltf::Camera& c = m.cameras[static_cast<std::size_t>(index)];
  if (c.type != "perspective") {
    unused.add("camera " + c.type, itemWhere("cameras", std::size_t(index)), "camera type '" + oneLine(c.type, 20) + "' not used by montecl");
    return;
  }
  Camera cam;
  cam.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
  cam.target = cam.position + glm::vec3(glm::normalize(glm::dmat3(world) * glm::dvec3(0, 0, -1)));
  cam.up = glm::vec3(glm::normalize(glm::dmat3(world) * glm::dvec3(0, 1, 0)));
  cam.fovY = static_cast<float>(glm::degrees(c.perspective.yfov));
  const double aspect = c.perspective.aspectRatio;
  cam.height = 512;
  cam.width = aspect > 0.0 && aspect < 32.0 ? std::max(1, static_cast<int>(std::lround(512.0 * aspect))) : 512;
  cameras.push_back(cam);  // the first is the camera; `render --camera N` picks another (and says so)
}

}  // namespace

bool loadGltfInto(const std::string& path, Scene& scene, std::vector<std::string>* warnings, Camera* camera,
                  std::optional<unsigned> sceneIndex) {
  std::vector<std::string> opened;  // external buffers and images, as opened (decoded URIs)
  const Model m = readGltfModel(path, warnings, &opened);
  scene.inputFiles.push_back(path);
  scene.inputFiles.insert(scene.inputFiles.end(), opened.begin(), opened.end());
  Loader l{path, m, scene, KindWarnings(path)};
  checkGltfSamplers(path, m);
  for (const std::string& e : m.extensionsUsed)
    if (!gltfExtensionSupported(e))
      l.unused.add("extension " + e, "extensionsUsed", "extension '" + oneLine(e, 60) + "' not used by montecl, ignored");
  if (!m.animations.empty()) l.unused.add("animations", "animations", "animations not used by montecl (the rest pose is rendered)");
  if (!m.skins.empty()) l.unused.add("skins", "skins", "skins not used by montecl (the rest pose is rendered)");
  const std::size_t sceneChosen = gltfSceneIndex(path, m, sceneIndex);
  const std::vector<int> roots = gltfRootNodes(m, sceneChosen);
  const std::size_t before = scene.triangles.size(), droppedBefore = scene.degenerateDropped;
  const std::size_t missingBefore = scene.missingTextures.size();
  std::uint64_t instanced = 0;  // triangles the meshes of the nodes so far declare
  // Pass 1: every node's placements of its mesh (EXT_mesh_gpu_instancing: world x instance
  // matrix, in instance order), in traversal order; cameras and lights as met.
  struct Placed {  // the matrices are made in pass 2, after the memory check of them all
    std::size_t node, mesh;
    glm::dmat4 world;
    GltfInstances inst;
    std::vector<glm::dmat4> at() const {
      std::vector<glm::dmat4> out(inst.count, world);
      if (inst.present) for (std::size_t k = 0; k < inst.count; ++k) out[k] = world * inst.local(k);
      return out;
    }
  };
  std::vector<Placed> placements;
  std::vector<std::uint64_t> uses(m.meshes.size(), 0);
  GltfPlacementBudget budget(m, before);
  std::vector<bool> visited(m.nodes.size(), false);
  std::vector<std::pair<int, glm::dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::dmat4(1.0));
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    if (index < 0 || static_cast<std::size_t>(index) >= m.nodes.size()) loadFail(path, "nodes", "node index " + std::to_string(index) + " out of range");
    const std::size_t i = static_cast<std::size_t>(index);
    if (visited[i]) loadFail(path, itemWhere("nodes", i), "node reached twice (a cycle, or a node with two parents)");
    visited[i] = true;
    const tinygltf::Node& node = m.nodes[i];
    const glm::dmat4 world = parent * gltfLocalTransform(path, node, itemWhere("nodes", i));
    if (node.camera != -1) l.takeCamera(node.camera, world, itemWhere("nodes", i) + ".camera");
    if (const int light = gltfNodeLight(node); light != -1) addGltfLight(path, m, light, world, scene, l.unused);
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= m.meshes.size()) loadFail(path, itemWhere("nodes", i), "mesh index out of range");
      Placed p{i, std::size_t(node.mesh), world, gltfNodeInstances(path, m, node, itemWhere("nodes", i))};
      for (const std::string& a : p.inst.ignored)
        l.unused.add("instance attribute " + a, itemWhere("nodes", i),
                     "instance attribute " + oneLine(a, 40) + " not used by montecl, ignored");
      uses[p.mesh] += p.inst.count;
      budget.add(i, p.mesh, p.inst.count);
      placements.push_back(std::move(p));
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, world);
  }
  std::size_t overNode = 0;  // every placement counted before one matrix is made
  if (const std::string many = budget.refusal(overNode); !many.empty())
    loadFail(path, itemWhere("nodes", overNode), "instancing its meshes " + many);
  // Pass 2: a mesh placed more than once is read once, in its own space, as a mesh range placed
  // by each placement (Scene::instances, a two-level BVH: memory grows with the unique meshes),
  // unless it emits (the emitter table is world space): then, as a mesh placed once, a copy per
  // placement. Every copy counts against the memory check (up to 2^40, so the sum cannot wrap).
  std::vector<std::int64_t> rangeOf(m.meshes.size(), -1);  // scene mesh range; -1 not read, -2 copies
  const std::uint64_t cap = std::uint64_t(1) << 40;
  const auto refuseBeyond = [&](std::uint64_t more, std::size_t node) {
    instanced = std::min(instanced + more, cap);
    const std::string tooMany = sceneMemoryRefusal(std::uint64_t(before) + instanced, sizeof(SceneTriangle));
    if (!tooMany.empty()) loadFail(path, itemWhere("nodes", node), "instancing its meshes " + tooMany);
  };
  bool ranges = false;
  for (const Placed& p : placements) {
    const tinygltf::Mesh& mesh = m.meshes[p.mesh];
    const std::string meshWhere = itemWhere("meshes", p.mesh);
    const std::uint64_t tris = std::min(gltfMeshTriangles(m, mesh), cap);
    if (uses[p.mesh] > 1 && rangeOf[p.mesh] == -1) {
      refuseBeyond(tris, p.node);
      const std::size_t first = scene.triangles.size(), dropped = scene.degenerateDropped;
      for (std::size_t q = 0; q < mesh.primitives.size(); ++q)
        l.primitive(mesh.primitives[q], glm::dmat4(1.0), meshWhere + ".primitives[" + std::to_string(q) + "]");
      if (scene.triangles.size() > first && !trianglesEmit(scene, first)) {
        const std::string many = instanceMemoryRefusal(std::uint64_t(scene.instances.size()) + uses[p.mesh]);
        if (!many.empty()) loadFail(path, itemWhere("nodes", p.node), "instancing its meshes " + many);
        rangeOf[p.mesh] = std::int64_t(scene.meshRanges.size());
        scene.meshRanges.push_back({std::uint32_t(first), std::uint32_t(scene.triangles.size() - first)});
        ranges = true;
      } else {  // copies after all: undo the unplaced read
        rangeOf[p.mesh] = -2;
        scene.triangles.resize(first);
        truncateCorners(scene, first);
        scene.degenerateDropped = dropped;
        instanced -= std::min(instanced, tris);
      }
    }
    if (rangeOf[p.mesh] >= 0) {
      const std::uint32_t r = std::uint32_t(rangeOf[p.mesh]);
      if (const std::string bad = addPlacements(scene, r, p.at()); !bad.empty())
        loadFail(path, meshWhere, "a node transform " + bad);
      continue;
    }
    const std::uint64_t copies = std::min<std::uint64_t>(p.inst.count, cap);
    refuseBeyond(copies != 0 && tris > cap / copies ? cap : tris * copies, p.node);
    for (const glm::dmat4& at : p.at())
      for (std::size_t q = 0; q < mesh.primitives.size(); ++q)
        l.primitive(mesh.primitives[q], at, meshWhere + ".primitives[" + std::to_string(q) + "]");
  }
  if (ranges) recomputeBounds(scene);  // appendTriangle grew them by object-space triangles too
  failOnMissingTextures(scene, missingBefore);
  l.unused.flush(warnings);
  if (scene.triangles.size() == before)
    loadFail(path, "", "no triangles (" + (l.skippedPrimitives ? std::to_string(l.skippedPrimitives) + " point or line primitives skipped, " : "") +
                           std::to_string(scene.degenerateDropped - droppedBefore) + " degenerate triangles dropped)");
  if (camera && !l.cameras.empty()) *camera = l.cameras[0];
  if (camera) scene.fileCameras = l.cameras;  // a bare model: `render --camera N` picks among them
  scene.fileScenes = m.scenes.size(), scene.fileScene = sceneChosen;
  return !l.cameras.empty();
}

}  // namespace montecl
