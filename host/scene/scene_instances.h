// scene_instances.h: a scene's instanced geometry (Scene::meshRanges, Scene::instances): which
// triangles are in world space, the instances' placed boxes, and flattening into placed copies.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// 1 for each triangle inside a mesh range (object space), 0 for a world-space one.
std::vector<std::uint8_t> instancedTriangles(const Scene& scene);

// The 8 world-space corners of every instance's box (its range's object-space bounds, placed), in
// instance order: what bounds, framing and ray offsets take for the placed copies.
std::vector<glm::vec3> instanceBoxCorners(const Scene& scene);

// Whether a triangle from `first` on has an emitting material (Ke > 0 or an emission texture):
// such meshes stay placed copies, since the emitter table is built in world space.
bool trianglesEmit(const Scene& scene, std::size_t first);

// The 8 corners of the object-space bounding box of a mesh range's triangles.
std::vector<glm::vec3> rangeBoxCorners(const Scene& scene, const MeshRange& range);

// Appends an instance of mesh range `range` at each matrix of `at`: a singular one (it would
// flatten every copy) is left out and its triangles counted in degenerateDropped. Returns what is
// wrong (nothing more appended) when one moves the range's box past the world's float range or
// its inverse out of float range (scene/value_limits.h placementProblem), else "".
std::string addPlacements(Scene& scene, std::uint32_t range, const std::vector<glm::dmat4>& at);

// The triangles of mesh ranges [firstRange, end), moved out of a scene with their corner colours
// and tangents (detachRanges; the other triangles keep their order, the ranges' firstTri then index
// `triangles` here), and appended back after the scene's triangles (attachRanges), so that
// whatever applies to a file's world-space triangles can run over one contiguous run of them.
struct DetachedRanges {
  std::vector<SceneTriangle> triangles;
  std::vector<glm::vec3> colours;   // 3 per triangle when the scene has vertex colours
  std::vector<glm::vec4> tangents;  // 3 per triangle when the scene has corner tangents
};

// A triangle's per-corner data kept beside it (Scene::vertexColors, vertexTangents), carried with
// it wherever it is placed, moved or dropped: white and zero where the scene holds none.
struct TriangleCorners {
  glm::vec3 colour[3]{glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f)};
  glm::vec4 tangent[3]{};
};
TriangleCorners cornersOf(const Scene& scene, std::size_t i);
// Writes triangle i's corners into each of the scene's arrays that reaches that far.
void putCorners(Scene& scene, std::size_t i, const TriangleCorners& c);
// Gives the triangle just appended as scene.triangles[i] its corner colours and tangents, each
// only when given (null: it has none; the array is padded up to it when a later one has some).
void appendCorners(Scene& scene, std::size_t i, const glm::vec3* colour, const glm::vec4* tangent);
// Drops the corner data of the triangles from `count` on (the triangles were cut there).
void truncateCorners(Scene& scene, std::size_t count);
DetachedRanges detachRanges(Scene& scene, std::size_t firstRange);
void attachRanges(Scene& scene, std::size_t firstRange, DetachedRanges detached);

// Why a scene must not hold `instances` placements: each costs instanceBytes(), its SceneInstance,
// its device Instance and, in the top level's build, about what a triangle costs (buildBvh over
// the boxes); "" when that fits hostMemoryBytes(). Otherwise "gives N instances: needs about X GiB ...".
std::uint64_t instanceBytes();
std::string instanceMemoryRefusal(std::uint64_t instances);

// Triangles a flattened scene would hold: the world ones plus every instance's copy.
std::uint64_t placedTriangleCount(const Scene& scene);

// A transform as triangles are placed by it: the matrix, its normals' matrix (the inverse
// transpose) and whether it mirrors, computed once for all the triangles it places.
struct Placement {
  explicit Placement(const glm::dmat4& m);
  // A corner tangent t (xyz unit, w the handedness) placed: xyz by the matrix's linear part (a
  // tangent is a direction along the surface, not a normal), unit again (zero when it cannot be);
  // w negated by a mirroring map, which turns cross(N, T) the other way relative to the placed
  // bitangent.
  glm::vec4 tangent(const glm::vec4& t) const;
  glm::dmat4 m;
  glm::dmat3 normalMatrix;
  bool mirror;
};
enum class Placed { Ok, OutOfRange, Degenerate };

// Places t by p, as every loader places a mesh's triangles (in double, normals by the inverse
// transpose, tangents by Placement::tangent, a mirroring map swaps the winding, and with it the
// corners' colours and tangents).
Placed placeTriangle(SceneTriangle& t, TriangleCorners& corners, const Placement& p);

// Replaces the ranges from firstRange on by one placed copy per instance of them, appended after
// the other triangles in instance order (degenerate copies dropped): with firstRange 0, the scene
// the loaders gave before instancing. The ranges before firstRange must lie before the others.
// Returns why not ("flattening its instances into copies gives N triangles: ...", nothing
// changed) when the copies would not fit the memory check (util/host_memory.h), else "".
std::string flattenInstances(Scene& scene, std::size_t firstRange = 0);

}  // namespace montecl
