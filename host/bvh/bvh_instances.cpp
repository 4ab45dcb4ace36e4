// bvh_instances.cpp: builds the two-level BVH (bottom levels per mesh with buildBvh, collapsed
// wide and rebased into one node and triangle array; the top level over padded world boxes of
// the instances) and runs the host reference traversal of it (kernels/shared/traverse_instances.h).
#include "bvh/bvh_instances.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kernels/shared/traverse_instances.h"
#include "scene/scene_instances.h"

namespace montecl {

namespace {

constexpr std::size_t kMaxWideRefs = std::size_t(1) << 27;  // the wide leaf encoding's limit

std::uint32_t rebaseRef(std::uint32_t ref, std::uint32_t nodeBase, std::uint32_t triBase) {
  if (ref == MCL_WIDE_EMPTY) return ref;
  if (ref & MCL_WIDE_LEAF) {
    const std::uint32_t first = wide_leaf_first(ref) + triBase;
    return MCL_WIDE_LEAF | (first << 4) | (ref & 15u);
  }
  return ref + nodeBase;
}

void setRows(float4* rows, const glm::dmat4& m) {
  for (int r = 0; r < 3; ++r)
    rows[r] = float4(float(m[0][r]), float(m[1][r]), float(m[2][r]), float(m[3][r]));
}

}  // namespace

std::size_t TwoLevelBvh::bytes() const {
  return nodes.size() * sizeof(WideNode) + triangles.size() * sizeof(Triangle) + instances.size() * sizeof(Instance);
}

TwoLevelBvh buildTwoLevelBvh(const std::vector<std::vector<SceneTriangle>>& meshes,
                             const std::vector<BvhInstanceDesc>& instances, const BvhBuildOptions& options) {
  TwoLevelBvh out;
  // Bottom levels, collapsed wide; their interior refs are rebased once the top level's size is known.
  std::vector<std::vector<WideNode>> bottoms(meshes.size());
  std::vector<glm::vec3> meshLo(meshes.size()), meshHi(meshes.size());
  std::size_t triCount = 0;
  int bottomDepth = 0;
  out.meshRoot.assign(meshes.size(), MCL_WIDE_EMPTY);
  out.meshTriBase.assign(meshes.size(), 0);
  out.meshTriCount.assign(meshes.size(), 0);
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (meshes[m].empty()) continue;
    Bvh b = buildBvh(meshes[m], options);
    if (triCount + b.triangles.size() > kMaxWideRefs)
      throw std::invalid_argument("buildTwoLevelBvh: more than 2^27 triangles in the bottom levels");
    const std::uint32_t triBase = static_cast<std::uint32_t>(triCount);
    out.meshTriBase[m] = triBase;
    out.meshTriCount[m] = static_cast<std::uint32_t>(b.triangles.size());
    for (std::size_t i = 0; i < b.triangles.size(); ++i) {
      Triangle t = b.triangles[i];
      t.e1.w = as_float(as_uint(t.e1.w) + triBase);
      out.triangles.push_back(t);
      out.triangleSource.push_back(b.order[i]);
    }
    triCount += b.triangles.size();
    bottoms[m] = b.wideNodes();
    for (WideNode& w : bottoms[m])
      for (std::uint32_t& c : w.child) c = rebaseRef(c, 0, triBase);  // triangles now; nodes below
    const BvhNode& root = b.nodes[0];
    meshLo[m] = glm::vec3(root.minX, root.minY, root.minZ);
    meshHi[m] = glm::vec3(root.maxX, root.maxY, root.maxZ);
    bottomDepth = std::max(bottomDepth, b.depth);
  }

  // The top level: each kept instance as a "triangle" spanning its padded world box (the box's
  // corners; buildBvh bins boxes and their centres), one per leaf, object splits only.
  std::vector<SceneTriangle> boxes;
  std::vector<Instance> kept;
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const BvhInstanceDesc& d = instances[k];
    const std::string where = "buildTwoLevelBvh: instance " + std::to_string(k);
    if (d.mesh >= meshes.size()) throw std::invalid_argument(where + ": mesh index out of range");
    const glm::dmat4 m(d.objectToWorld);
    const glm::dmat4 inv = glm::inverse(m);
    bool finite = true;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(m[c][r]) && std::isfinite(inv[c][r]);
    const double det = glm::determinant(glm::dmat3(m));
    if (!finite || !(std::fabs(det) > 0.0) || m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
      throw std::invalid_argument(where + ": the transform is not an invertible finite affine map");
    if (meshes[d.mesh].empty()) continue;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 p((c & 1) ? meshHi[d.mesh].x : meshLo[d.mesh].x, (c & 2) ? meshHi[d.mesh].y : meshLo[d.mesh].y,
                        (c & 4) ? meshHi[d.mesh].z : meshLo[d.mesh].z);
      const glm::vec3 w(d.objectToWorld * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
    // Padding: the ray is tested against the world box in world space and against the
    // triangles in object space; their roundings differ by far less than this.
    const float pad = std::max(glm::length(hi - lo), std::max(glm::length(lo), glm::length(hi))) * 0x1p-18f + 1e-30f;
    lo -= glm::vec3(pad);
    hi += glm::vec3(pad);
    SceneTriangle box;
    box.v[0] = lo;
    box.v[1] = hi;
    box.v[2] = hi;
    box.material = 0;
    boxes.push_back(box);
    Instance in{};
    setRows(in.worldToObject, inv);
    setRows(in.objectToWorld, m);
    in.root = 0;  // set below
    in.triBase = out.meshTriBase[d.mesh];
    in.mesh = d.mesh;
    in.id = static_cast<std::uint32_t>(k);
    kept.push_back(in);
  }
  if (kept.size() > kMaxWideRefs) throw std::invalid_argument("buildTwoLevelBvh: more than 2^27 instances");

  if (kept.empty()) {
    out.nodes.push_back(emptyWideNode());
  } else {
    BvhBuildOptions top = options;
    top.splitBudget = 0.0f;
    top.maxLeafSize = 1;
    Bvh t = buildBvh(boxes, top);
    out.nodes = t.wideNodes();  // leaf refs: ranges of the instances in leaf order
    out.depth = t.depth;
    out.instances.reserve(kept.size());
    for (std::uint32_t slot : t.order) out.instances.push_back(kept[slot]);
  }
  out.depth += bottomDepth;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (bottoms[m].empty()) continue;
    const std::uint32_t nodeBase = static_cast<std::uint32_t>(out.nodes.size());
    out.meshRoot[m] = nodeBase;
    for (WideNode w : bottoms[m]) {
      for (std::uint32_t& c : w.child)
        if (c != MCL_WIDE_EMPTY && !(c & MCL_WIDE_LEAF)) c += nodeBase;
      out.nodes.push_back(w);
    }
    std::vector<WideNode>().swap(bottoms[m]);
  }
  for (Instance& in : out.instances) in.root = out.meshRoot[in.mesh];
  return out;
}

Bvh sceneView(const TwoLevelBvh& bvh, const std::vector<std::uint32_t>& meshFirstTri) {
  if (meshFirstTri.size() != bvh.meshTriBase.size())
    throw std::invalid_argument("sceneView: one first triangle per mesh expected");
  Bvh v;
  v.nodes = {emptyBinaryNode()};
  v.triangles = bvh.triangles;
  v.order.resize(bvh.triangles.size());
  for (std::size_t m = 0; m < meshFirstTri.size(); ++m)
    for (std::uint32_t i = 0; i < bvh.meshTriCount[m]; ++i) {
      const std::uint32_t slot = bvh.meshTriBase[m] + i;
      v.order[slot] = meshFirstTri[m] + bvh.triangleSource[slot];
    }
  std::size_t inputs = 0;
  for (std::size_t i = 0; i < v.triangles.size(); ++i) inputs += as_uint(v.triangles[i].e1.w) == i;
  v.inputCount = inputs;
  v.depth = bvh.depth;
  v.wideCache.preset(bvh.nodes);
  return v;
}

Bvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options) {
  if (scene.instances.empty() && scene.meshRanges.empty()) return buildBvh(scene.triangles, options);
  const std::vector<std::uint8_t> instanced = instancedTriangles(scene);
  std::vector<std::vector<SceneTriangle>> meshes(1 + scene.meshRanges.size());
  std::vector<std::uint32_t> worldIndex;  // mesh 0's triangle k is scene triangle worldIndex[k]
  for (std::size_t i = 0; i < scene.triangles.size(); ++i)
    if (!instanced[i]) {
      meshes[0].push_back(scene.triangles[i]);
      worldIndex.push_back(static_cast<std::uint32_t>(i));
    }
  std::vector<std::uint32_t> meshFirstTri(meshes.size(), 0);
  for (std::size_t r = 0; r < scene.meshRanges.size(); ++r) {
    const MeshRange& range = scene.meshRanges[r];
    meshes[1 + r].assign(scene.triangles.begin() + range.firstTri, scene.triangles.begin() + range.firstTri + range.count);
    meshFirstTri[1 + r] = range.firstTri;
  }
  std::vector<BvhInstanceDesc> placed;
  placed.reserve(1 + scene.instances.size());
  if (!meshes[0].empty()) placed.push_back(BvhInstanceDesc{0, glm::mat4(1.0f)});
  for (const SceneInstance& in : scene.instances) placed.push_back(BvhInstanceDesc{1 + in.range, glm::mat4(in.objectToWorld)});
  const TwoLevelBvh two = buildTwoLevelBvh(meshes, placed, options);
  std::vector<std::vector<SceneTriangle>>().swap(meshes);
  Bvh v = sceneView(two, meshFirstTri);
  for (std::uint32_t i = 0; i < two.meshTriCount[0]; ++i) {  // mesh 0 is not one run of the scene's triangles
    const std::uint32_t slot = two.meshTriBase[0] + i;
    v.order[slot] = worldIndex[two.triangleSource[slot]];
  }
  v.instances = two.instances;
  return v;
}

TwoLevelHit intersectClosest(const TwoLevelBvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                             const AlphaScene* alpha) {
  TwoLevelHit r;
  r.hit.t = INFINITY;
  r.hit.tri = MCL_NO_HIT;
  r.hit.u = r.hit.v = 0.0f;
  r.instance = MCL_NO_INSTANCE;
  if (bvh.nodes.empty() || bvh.instances.empty()) return r;
  const InstanceHit h =
      instances_closest_hit(bvh.nodes.data(), bvh.triangles.data(), bvh.instances.data(), alpha, org, dir, tmax);
  r.hit = h.hit;
  r.instance = h.instance == MCL_NO_INSTANCE ? MCL_NO_INSTANCE : bvh.instances[h.instance].id;
  return r;
}

bool intersectAny(const TwoLevelBvh& bvh, const glm::vec3& org, const glm::vec3& dir, float tmax,
                  const AlphaScene* alpha) {
  if (bvh.nodes.empty() || bvh.instances.empty()) return false;
  return instances_any_hit(bvh.nodes.data(), bvh.triangles.data(), bvh.instances.data(), alpha, org, dir, tmax) != 0;
}

}  // namespace montecl
