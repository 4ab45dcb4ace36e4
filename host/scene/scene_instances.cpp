// scene_instances.cpp: the instanced geometry of a scene: masks, placed boxes, flattening; the
// per-corner data (colours, tangents) that follows triangles when they move.
#include "scene/scene_instances.h"

#include <cmath>
#include <utility>

#include "kernels/shared/types.h"
#include "scene/value_limits.h"
#include "util/host_memory.h"

namespace montecl {

std::vector<std::uint8_t> instancedTriangles(const Scene& scene) {
  std::vector<std::uint8_t> in(scene.triangles.size(), 0);
  for (const MeshRange& r : scene.meshRanges)
    for (std::uint32_t i = 0; i < r.count; ++i) in[r.firstTri + i] = 1;
  return in;
}

bool trianglesEmit(const Scene& scene, std::size_t first) {
  std::vector<std::uint8_t> seen(scene.materials.size(), 0);
  for (std::size_t t = first; t < scene.triangles.size(); ++t) {
    const std::uint32_t m = scene.triangles[t].material;
    if (seen[m]) continue;
    seen[m] = 1;
    const MaterialDesc& d = scene.materials[m];
    if (d.emission.x > 0.0f || d.emission.y > 0.0f || d.emission.z > 0.0f || !d.emissionTexture.empty()) return true;
  }
  return false;
}

std::vector<glm::vec3> rangeBoxCorners(const Scene& scene, const MeshRange& range) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (std::uint32_t i = 0; i < range.count; ++i)
    for (const glm::vec3& v : scene.triangles[range.firstTri + i].v) lo = glm::min(lo, v), hi = glm::max(hi, v);
  std::vector<glm::vec3> corners;
  for (int c = 0; c < 8; ++c) corners.push_back({(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z});
  return corners;
}

std::string addPlacements(Scene& scene, std::uint32_t range, const std::vector<glm::dmat4>& at) {
  const std::vector<glm::vec3> box = rangeBoxCorners(scene, scene.meshRanges[range]);
  for (const glm::dmat4& m : at) {
    if (!(glm::determinant(glm::dmat3(m)) != 0.0)) {
      scene.degenerateDropped += scene.meshRanges[range].count;
      continue;
    }
    if (std::string problem = placementProblem(m, box); !problem.empty()) return problem;
    scene.instances.push_back({range, m});
  }
  return "";
}

std::vector<glm::vec3> instanceBoxCorners(const Scene& scene) {
  std::vector<glm::vec3> lo(scene.meshRanges.size(), glm::vec3(INFINITY)), hi(scene.meshRanges.size(), glm::vec3(-INFINITY));
  for (std::size_t r = 0; r < scene.meshRanges.size(); ++r)
    for (std::uint32_t i = 0; i < scene.meshRanges[r].count; ++i)
      for (const glm::vec3& v : scene.triangles[scene.meshRanges[r].firstTri + i].v) {
        lo[r] = glm::min(lo[r], v);
        hi[r] = glm::max(hi[r], v);
      }
  std::vector<glm::vec3> corners;
  corners.reserve(8 * scene.instances.size());
  for (const SceneInstance& in : scene.instances) {
    if (scene.meshRanges[in.range].count == 0) continue;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 p((c & 1) ? hi[in.range].x : lo[in.range].x, (c & 2) ? hi[in.range].y : lo[in.range].y,
                         (c & 4) ? hi[in.range].z : lo[in.range].z);
      corners.push_back(glm::vec3(in.objectToWorld * glm::dvec4(p, 1.0)));
    }
  }
  return corners;
}

std::uint64_t instanceBytes() { return sizeof(SceneInstance) + sizeof(Instance) + sizeof(SceneTriangle) + 125; }

std::string instanceMemoryRefusal(std::uint64_t instances) {
  const std::uint64_t need = instances * instanceBytes(), has = hostMemoryBytes();
  if (need <= has) return "";
  return "gives " + std::to_string(instances) + " instances: needs about " + gibText(need) +
         " of memory (placements and their BVH), this machine has " + gibText(has);
}

std::uint64_t placedTriangleCount(const Scene& scene) {
  std::uint64_t n = scene.triangles.size();
  for (const MeshRange& r : scene.meshRanges) n -= r.count;
  for (const SceneInstance& in : scene.instances) n += scene.meshRanges[in.range].count;
  return n;
}

Placement::Placement(const glm::dmat4& matrix)
    : m(matrix), normalMatrix(glm::transpose(glm::inverse(glm::dmat3(matrix)))), mirror(glm::determinant(glm::dmat3(matrix)) < 0.0) {}

glm::vec4 Placement::tangent(const glm::vec4& t) const {
  const glm::dvec3 d = glm::dmat3(m) * glm::dvec3(t);
  const double len = glm::length(d);
  const glm::vec3 unit = len > 0.0 && std::isfinite(len) ? glm::vec3(d / len) : glm::vec3(0.0f);
  return glm::vec4(unit, mirror ? -t.w : t.w);
}

Placed placeTriangle(SceneTriangle& t, TriangleCorners& corners, const Placement& p) {
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (int k = 0; k < 3; ++k) {
    t.v[k] = glm::vec3(p.m * glm::dvec4(glm::dvec3(t.v[k]), 1.0));
    if (!finite(t.v[k])) return Placed::OutOfRange;
    if (t.attributes & kHasNormals) t.n[k] = glm::vec3(glm::normalize(p.normalMatrix * glm::dvec3(t.n[k])));
    if (t.attributes & kHasTangents) corners.tangent[k] = p.tangent(corners.tangent[k]);
  }
  if (p.mirror) {  // keep the winding's side: the face normal follows the mirrored surface
    std::swap(t.v[1], t.v[2]);
    std::swap(t.n[1], t.n[2]);
    std::swap(t.uv[1], t.uv[2]);
    std::swap(corners.colour[1], corners.colour[2]);
    std::swap(corners.tangent[1], corners.tangent[2]);
  }
  const glm::vec3 n = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
  return finite(n) && n != glm::vec3(0.0f) ? Placed::Ok : Placed::Degenerate;
}

namespace {

// Splits a per-corner array a of `triangles` triangles (3 each; fill past its end): the corners of
// the triangles listed in `order` are returned in that order, the others (moving[i] == 0) kept in
// a, in their order. Nothing when a is empty (the scene has no such data).
template <class T>
std::vector<T> splitCorners(std::vector<T>& a, std::size_t triangles, const std::vector<std::uint8_t>& moving,
                            const std::vector<std::size_t>& order, const T& fill) {
  std::vector<T> out;
  if (a.empty()) return out;
  a.resize(3 * triangles, fill);
  for (std::size_t i : order) out.insert(out.end(), a.begin() + std::ptrdiff_t(3 * i), a.begin() + std::ptrdiff_t(3 * i + 3));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < triangles; ++i)
    if (!moving[i]) {
      for (std::size_t k = 0; k < 3; ++k) a[3 * kept + k] = a[3 * i + k];
      ++kept;
    }
  a.resize(3 * kept);
  return out;
}

// Appends `more` (the corners of `count` triangles; empty: they have none) to a, which holds `base`
// triangles' (padded with fill): nothing when neither has any.
template <class T>
void joinCorners(std::vector<T>& a, std::size_t base, std::vector<T> more, std::size_t count, const T& fill) {
  if (more.empty() && a.empty()) return;
  a.resize(3 * base, fill);
  if (more.empty()) more.assign(3 * count, fill);
  a.insert(a.end(), more.begin(), more.end());
}

// Pads a (with fill) up to triangle i and appends its three corners c.
template <class T>
void appendCornersOf(std::vector<T>& a, std::size_t i, const T* c, const T& fill) {
  a.resize(3 * i, fill);
  a.insert(a.end(), c, c + 3);
}

}  // namespace

TriangleCorners cornersOf(const Scene& scene, std::size_t i) {
  TriangleCorners c;
  for (std::size_t k = 0; k < 3; ++k) {
    if (3 * i + 2 < scene.vertexColors.size()) c.colour[k] = scene.vertexColors[3 * i + k];
    if (3 * i + 2 < scene.vertexTangents.size()) c.tangent[k] = scene.vertexTangents[3 * i + k];
  }
  return c;
}

void putCorners(Scene& scene, std::size_t i, const TriangleCorners& c) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (3 * i + 2 < scene.vertexColors.size()) scene.vertexColors[3 * i + k] = c.colour[k];
    if (3 * i + 2 < scene.vertexTangents.size()) scene.vertexTangents[3 * i + k] = c.tangent[k];
  }
}

void appendCorners(Scene& scene, std::size_t i, const glm::vec3* colour, const glm::vec4* tangent) {
  if (colour) appendCornersOf(scene.vertexColors, i, colour, glm::vec3(1.0f));
  if (tangent) appendCornersOf(scene.vertexTangents, i, tangent, glm::vec4(0.0f));
}

void truncateCorners(Scene& scene, std::size_t count) {
  if (scene.vertexColors.size() > 3 * count) scene.vertexColors.resize(3 * count);
  if (scene.vertexTangents.size() > 3 * count) scene.vertexTangents.resize(3 * count);
}

DetachedRanges detachRanges(Scene& scene, std::size_t firstRange) {
  DetachedRanges d;
  std::vector<std::uint8_t> moving(scene.triangles.size(), 0);
  std::vector<std::size_t> order;  // the moving triangles, in range order
  for (std::size_t r = firstRange; r < scene.meshRanges.size(); ++r) {
    MeshRange& range = scene.meshRanges[r];
    const std::uint32_t first = static_cast<std::uint32_t>(d.triangles.size());
    for (std::uint32_t i = 0; i < range.count; ++i) {
      moving[range.firstTri + i] = 1;
      order.push_back(range.firstTri + i);
      d.triangles.push_back(scene.triangles[range.firstTri + i]);
    }
    range.firstTri = first;
  }
  d.colours = splitCorners(scene.vertexColors, scene.triangles.size(), moving, order, glm::vec3(1.0f));
  d.tangents = splitCorners(scene.vertexTangents, scene.triangles.size(), moving, order, glm::vec4(0.0f));
  std::size_t out = 0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i)
    if (!moving[i]) scene.triangles[out++] = scene.triangles[i];
  scene.triangles.resize(out);
  return d;
}

void attachRanges(Scene& scene, std::size_t firstRange, DetachedRanges d) {
  const std::uint32_t base = static_cast<std::uint32_t>(scene.triangles.size());
  for (std::size_t r = firstRange; r < scene.meshRanges.size(); ++r) scene.meshRanges[r].firstTri += base;
  joinCorners(scene.vertexColors, base, std::move(d.colours), d.triangles.size(), glm::vec3(1.0f));
  joinCorners(scene.vertexTangents, base, std::move(d.tangents), d.triangles.size(), glm::vec4(0.0f));
  scene.triangles.insert(scene.triangles.end(), d.triangles.begin(), d.triangles.end());
}

std::string flattenInstances(Scene& scene, std::size_t firstRange) {
  if (firstRange >= scene.meshRanges.size()) return "";
  // Every copy is counted against the memory check before one is made.
  std::uint64_t copies = scene.triangles.size();
  for (std::size_t r = firstRange; r < scene.meshRanges.size(); ++r) copies -= scene.meshRanges[r].count;
  for (const SceneInstance& in : scene.instances)
    if (in.range >= firstRange) copies += scene.meshRanges[in.range].count;
  if (std::string tooMany = sceneMemoryRefusal(copies, sizeof(SceneTriangle)); !tooMany.empty())
    return "flattening its instances into copies " + tooMany;
  std::vector<std::uint8_t> flattened(scene.triangles.size(), 0);  // in a range being flattened
  for (std::size_t r = firstRange; r < scene.meshRanges.size(); ++r)
    for (std::uint32_t i = 0; i < scene.meshRanges[r].count; ++i) flattened[scene.meshRanges[r].firstTri + i] = 1;
  const bool coloured = !scene.vertexColors.empty(), tangents = !scene.vertexTangents.empty();
  std::vector<SceneTriangle> out;
  std::vector<glm::vec3> colours;
  std::vector<glm::vec4> tangentsOut;
  const auto add = [&](const SceneTriangle& t, const TriangleCorners& c) {
    out.push_back(t);
    if (coloured) colours.insert(colours.end(), c.colour, c.colour + 3);
    if (tangents) tangentsOut.insert(tangentsOut.end(), c.tangent, c.tangent + 3);
  };
  for (std::size_t i = 0; i < scene.triangles.size(); ++i)
    if (!flattened[i]) add(scene.triangles[i], cornersOf(scene, i));
  std::vector<SceneInstance> kept;
  for (const SceneInstance& in : scene.instances) {
    if (in.range < firstRange) {
      kept.push_back(in);
      continue;
    }
    const MeshRange& r = scene.meshRanges[in.range];
    const Placement placement(in.objectToWorld);
    for (std::uint32_t k = 0; k < r.count; ++k) {
      const std::size_t i = r.firstTri + k;
      SceneTriangle t = scene.triangles[i];
      TriangleCorners c = cornersOf(scene, i);
      if (placeTriangle(t, c, placement) == Placed::Ok)
        add(t, c);
      else
        ++scene.degenerateDropped;
    }
  }
  scene.triangles = std::move(out);
  scene.vertexColors = std::move(colours);
  scene.vertexTangents = std::move(tangentsOut);
  scene.meshRanges.resize(firstRange);  // the ranges before firstRange lie before every flattened one
  scene.instances = std::move(kept);
  return "";
}

}  // namespace montecl
