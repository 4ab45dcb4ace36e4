// test_bvh_instances.cpp: the two-level BVH (host/bvh/bvh_instances.h, traversal
// kernels/shared/traverse_instances.h run on the host): closest and any hit through randomly
// placed instances (rotations, non-uniform and mirroring scales, coincident copies, an empty mesh)
// equal brute force over the flattened world-space triangles, with the same triangle and
// instance, and the hit's surface frame brought to world space is the flattened triangle's; the
// scene view (a Bvh over the two levels) maps each slot to its scene triangle; one identity
// instance is bit for bit the one-level BVH; memory grows with the instances, not with their
// triangles (10,000 bunnies in under twice one bunny's bytes).
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bvh/bvh.h"
#include "bvh/bvh_instances.h"
#include "render/triangle_shading.h"
#include "kernels/shared/geometry.h"
#include "kernels/shared/instance_space.h"
#include "kernels/shared/surface.h"
#include "skip.h"
#include "soups.h"

namespace test_file_bvh_instances {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using glm::vec3;

namespace {

struct WorldTri {
  vec3 v0, e1, e2;
  std::uint32_t instance, tri;  // input indices
};

struct BruteHit {
  float t = INFINITY, u = 0.0f, v = 0.0f;
  std::uint32_t instance = MCL_NO_INSTANCE, tri = MCL_NO_HIT;
};

// Every instance's triangles placed in world space, as a flattening loader would.
std::vector<WorldTri> flatten(const std::vector<std::vector<SceneTriangle>>& meshes,
                              const std::vector<BvhInstanceDesc>& inst) {
  std::vector<WorldTri> out;
  for (std::uint32_t k = 0; k < inst.size(); ++k)
    for (std::uint32_t i = 0; i < meshes[inst[k].mesh].size(); ++i) {
      const SceneTriangle& t = meshes[inst[k].mesh][i];
      vec3 p[3];
      for (int c = 0; c < 3; ++c) p[c] = vec3(inst[k].objectToWorld * glm::vec4(t.v[c], 1.0f));
      out.push_back({p[0], p[1] - p[0], p[2] - p[0], k, i});
    }
  return out;
}

BruteHit bruteClosest(const std::vector<WorldTri>& tris, vec3 o, vec3 d, float tmax) {
  BruteHit b;
  b.t = tmax;
  for (const WorldTri& w : tris) {
    float u, v;
    float t = ray_triangle(o, d, w.v0, w.e1, w.e2, b.t, &u, &v);
    if (t < b.t) b = {t, u, v, w.instance, w.tri};
  }
  if (b.tri == MCL_NO_HIT) b.t = INFINITY;
  return b;
}

// How far inside triangle w the ray passes (min of the barycentrics, unclamped; negative outside)
// and at which t.
float margin(const WorldTri& w, vec3 o, vec3 d, float* tOut) {
  vec3 p = glm::cross(d, w.e2);
  float inv = 1.0f / glm::dot(w.e1, p);
  vec3 s = o - w.v0;
  float u = glm::dot(s, p) * inv;
  vec3 q = glm::cross(s, w.e1);
  float v = glm::dot(d, q) * inv;
  *tOut = glm::dot(w.e2, q) * inv;
  return std::min(std::min(u, v), 1.0f - u - v);
}

const WorldTri& find(const std::vector<WorldTri>& tris, std::uint32_t instance, std::uint32_t tri) {
  for (const WorldTri& w : tris)
    if (w.instance == instance && w.tri == tri) return w;
  FAIL("no such flattened triangle");
  return tris[0];
}

glm::mat4 randomPlacement(std::mt19937& rng, bool mirror) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  vec3 axis = glm::normalize(vec3(u(rng), u(rng), u(rng)) - 0.5f + 1e-3f);
  vec3 scale(0.3f + 1.7f * u(rng), 0.3f + 1.7f * u(rng), 0.3f + 1.7f * u(rng));
  if (mirror) scale.y = -scale.y;
  glm::mat4 m = glm::translate(glm::mat4(1.0f), (vec3(u(rng), u(rng), u(rng)) - 0.5f) * 50.0f);
  m = glm::rotate(m, 6.2831853f * u(rng), axis);
  return glm::scale(m, scale);
}

struct Fixture {
  std::vector<std::vector<SceneTriangle>> meshes;
  std::vector<BvhInstanceDesc> inst;
};

Fixture makeFixture() {
  Fixture f;
  f.meshes.push_back(montecl_test::seededSoup(300, 11, 3.0f, 1.0f, 0.2f));
  f.meshes.push_back(montecl_test::seededSoup(120, 12, 6.0f, 2.0f, 0.5f));
  f.meshes.push_back({});  // no triangles: its instances are left out
  std::mt19937 rng(5);
  for (int k = 0; k < 60; ++k) f.inst.push_back({std::uint32_t(k % 3), randomPlacement(rng, k % 7 == 3)});
  const glm::mat4 same = randomPlacement(rng, false);
  for (int k = 0; k < 5; ++k) f.inst.push_back({1, same});  // coincident copies
  return f;
}

}  // namespace

TEST_CASE("bvh instances: closest and any hit through the two levels equal brute force over the flattened triangles" * doctest::test_suite("cpu")) {
  const Fixture f = makeFixture();
  const TwoLevelBvh bvh = buildTwoLevelBvh(f.meshes, f.inst);
  const std::vector<WorldTri> flat = flatten(f.meshes, f.inst);
  REQUIRE(bvh.triangles.size() >= 420);  // unique geometry only
  REQUIRE(bvh.instances.size() == 45);   // the 20 instances of the empty mesh left out
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int hits = 0, grazing = 0, ties = 0, n = 3000;
  for (int i = 0; i < n; ++i) {
    const vec3 o = (vec3(u(rng), u(rng), u(rng)) - 0.5f) * 70.0f;
    vec3 target = (vec3(u(rng), u(rng), u(rng)) - 0.5f) * 40.0f;
    const vec3 d = glm::normalize(target - o) * (0.5f + u(rng));  // not unit: t is the world t
    const float tmax = (i % 2) ? INFINITY : 80.0f * u(rng);
    const BruteHit ref = bruteClosest(flat, o, d, tmax);
    const TwoLevelHit got = intersectClosest(bvh, o, d, tmax);
    const bool any = intersectAny(bvh, o, d, tmax);
    CAPTURE(i);
    const bool refHit = ref.tri != MCL_NO_HIT, gotHit = got.hit.tri != MCL_NO_HIT;
    CHECK(gotHit == (got.instance != MCL_NO_INSTANCE));
    if (refHit) ++hits;
    if (refHit != gotHit || any != refHit) {
      // Only a ray grazing an edge (or meeting the hit at tmax) may be judged differently by the
      // world-space and the object-space test.
      const WorldTri& w = refHit ? find(flat, ref.instance, ref.tri)
                                 : find(flat, got.instance, bvh.triangleSource[got.hit.tri]);
      float t;
      const float m = margin(w, o, d, &t);
      CHECK((std::fabs(m) < 1e-4f || std::fabs(t - tmax) < 1e-4f * tmax));
      ++grazing;
      continue;
    }
    if (!refHit) continue;
    CHECK(std::fabs(got.hit.t - ref.t) <= 1e-4f * std::max(1.0f, ref.t));
    const std::uint32_t gotTri = bvh.triangleSource[got.hit.tri];
    const std::uint32_t gotMesh = f.inst[got.instance].mesh;
    REQUIRE(got.instance < f.inst.size());
    CHECK(got.hit.tri >= bvh.meshTriBase[gotMesh]);
    if (got.instance != ref.instance || gotTri != ref.tri) {
      // A (near) tie: the triangle reported must meet the ray at the closest distance too.
      float t;
      const float m = margin(find(flat, got.instance, gotTri), o, d, &t);
      CHECK(m > -1e-4f);
      CHECK(std::fabs(t - ref.t) <= 1e-4f * std::max(1.0f, ref.t));
      ++ties;
    } else {
      CHECK(std::fabs(got.hit.u - ref.u) < 1e-3f);
      CHECK(std::fabs(got.hit.v - ref.v) < 1e-3f);
    }
  }
  MESSAGE(hits << " of " << n << " rays hit; " << grazing << " grazing, " << ties << " ties");
  CHECK(hits > n / 4);
  CHECK(grazing <= n / 100);
}

TEST_CASE("bvh instances: one identity instance is the one-level BVH bit for bit" * doctest::test_suite("cpu")) {
  const std::vector<SceneTriangle> soup = montecl_test::seededSoup(500, 21, 4.0f, 1.0f, 0.1f);
  const Bvh one = buildBvh(soup);
  const TwoLevelBvh two = buildTwoLevelBvh({soup}, {BvhInstanceDesc{0, glm::mat4(1.0f)}});
  REQUIRE(two.triangles.size() == one.triangles.size());
  const std::vector<Ray> rays = montecl_test::seededRays(2000, 4, vec3(-7.0f), vec3(7.0f), 0.5f, 10.0f);
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const vec3 o(rays[i].origin), d(rays[i].dir);
    const float tmax = rays[i].dir.w;
    const Hit a = intersectClosest(one, o, d, tmax);
    const TwoLevelHit b = intersectClosest(two, o, d, tmax);
    CAPTURE(i);
    CHECK(as_uint(a.t) == as_uint(b.hit.t));
    CHECK(a.tri == b.hit.tri);
    CHECK(as_uint(a.u) == as_uint(b.hit.u));
    CHECK(as_uint(a.v) == as_uint(b.hit.v));
    CHECK(b.instance == (a.tri == MCL_NO_HIT ? MCL_NO_INSTANCE : 0u));
    CHECK(intersectAny(one, o, d, tmax) == intersectAny(two, o, d, tmax));
    hits += a.tri != MCL_NO_HIT;
  }
  CHECK(hits > 100);
}

TEST_CASE("bvh instances: memory grows with the instances, not with their triangles" * doctest::test_suite("cpu")) {
  const std::vector<SceneTriangle> mesh = montecl_test::seededSoup(20000, 31, 2.0f, 0.5f, 0.1f);
  const TwoLevelBvh one = buildTwoLevelBvh({mesh}, {BvhInstanceDesc{0, glm::mat4(1.0f)}});
  std::vector<BvhInstanceDesc> many;
  std::mt19937 rng(3);
  for (int k = 0; k < 10000; ++k) many.push_back({0, randomPlacement(rng, false)});
  const TwoLevelBvh lots = buildTwoLevelBvh({mesh}, many);
  CHECK(lots.triangles.size() == one.triangles.size());
  const double perInstance = double(lots.bytes() - one.bytes()) / 9999.0;
  MESSAGE("one mesh: " << one.bytes() << " bytes; 10000 instances: " << lots.bytes() << " bytes ("
                       << perInstance << " per instance)");
  CHECK(perInstance < 200.0);  // an Instance (112 bytes) and its share of the top level's nodes
  CHECK(lots.bytes() < 2 * one.bytes());
}

TEST_CASE("bvh instances: bad instances are refused" * doctest::test_suite("cpu")) {
  const std::vector<SceneTriangle> mesh = montecl_test::seededSoup(10, 1, 1.0f, 1.0f, 0.1f);
  CHECK_THROWS_AS(buildTwoLevelBvh({mesh}, {BvhInstanceDesc{1, glm::mat4(1.0f)}}), std::invalid_argument);
  CHECK_THROWS_AS(buildTwoLevelBvh({mesh}, {BvhInstanceDesc{0, glm::mat4(0.0f)}}), std::invalid_argument);
  glm::mat4 nan(1.0f);
  nan[3][0] = NAN;
  CHECK_THROWS_AS(buildTwoLevelBvh({mesh}, {BvhInstanceDesc{0, nan}}), std::invalid_argument);
}

TEST_CASE("bvh instances: a hit's object-space frame brought to world space is the flattened triangle's" * doctest::test_suite("cpu")) {
  const Fixture f = makeFixture();
  const TwoLevelBvh bvh = buildTwoLevelBvh(f.meshes, f.inst);
  const std::vector<WorldTri> flat = flatten(f.meshes, f.inst);
  std::vector<float4> normals;  // object space, per slot, as the renderer precomputes them
  for (const Triangle& t : bvh.triangles) normals.push_back(float4(glm::normalize(glm::cross(vec3(t.e1), vec3(t.e2))), 0.0f));
  const TriangleShading none{};
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int checked = 0, mirrored = 0, back = 0;
  for (int i = 0; i < 2000; ++i) {
    const vec3 o = (vec3(u(rng), u(rng), u(rng)) - 0.5f) * 70.0f;
    const vec3 d = glm::normalize((vec3(u(rng), u(rng), u(rng)) - 0.5f) * 40.0f - o);
    const TwoLevelHit got = intersectClosest(bvh, o, d, INFINITY);
    if (got.hit.tri == MCL_NO_HIT) continue;
    CAPTURE(i);
    const Instance* in = nullptr;
    for (const Instance& x : bvh.instances)
      if (x.id == got.instance) in = &x;
    REQUIRE(in != nullptr);
    const vec3 dObj = affine_vector(in->worldToObject, d);
    const SurfaceFrame s = instance_frame(in, surface_frame(bvh.triangles.data(), normals.data(), &none, got.hit, dObj));
    const WorldTri& w = find(flat, got.instance, bvh.triangleSource[got.hit.tri]);
    const float sign = glm::determinant(glm::mat3(f.inst[got.instance].objectToWorld)) < 0.0f ? -1.0f : 1.0f;
    const vec3 face = glm::normalize(glm::cross(w.e1, w.e2)) * sign;  // the flattened copy's normal (winding kept)
    const vec3 facing = glm::dot(face, d) > 0.0f ? -face : face;
    CHECK(glm::length(s.p - (o + got.hit.t * d)) <= 1e-4f * (glm::length(o) + got.hit.t + 1.0f));
    CHECK(glm::dot(s.ng, facing) > 1.0f - 1e-4f);
    CHECK(std::fabs(glm::length(s.ng) - 1.0f) < 1e-5f);
    CHECK(s.backface == (glm::dot(face, d) > 0.0f ? 1 : 0));
    ++checked;
    mirrored += sign < 0.0f;
    back += s.backface;
  }
  MESSAGE(checked << " hits checked, " << mirrored << " on mirrored instances, " << back << " back faces");
  CHECK(checked > 300);
  CHECK(mirrored > 10);
}

namespace {

std::vector<SceneTriangle> bunnyTriangles(const std::string& path) {
  std::vector<std::string> warnings;
  return loadScene(path, warnings).triangles;
}

// What the device holds per unique triangle besides the BVH: TriangleShading and the normals entry.
constexpr std::size_t kShadingBytes = sizeof(TriangleShading) + sizeof(float4);

}  // namespace

// The benchmark figure of docs/performance.md (peak RSS of each case run alone under
// /usr/bin/time -v): one bunny, then 10,000 placed bunnies.
TEST_CASE("bvh instances: one bunny, the baseline of the memory figure" * doctest::test_suite("cpu shared-scenes slow")) {
  const std::string path = montecl_test::sharedScenes() + "/bunny/bunny.obj";
  MCL_SKIP_UNLESS(std::ifstream(path), path << " not found (the shared scenes are not beside this checkout)");
  const std::vector<SceneTriangle> bunny = bunnyTriangles(path);
  const TwoLevelBvh one = buildTwoLevelBvh({bunny}, {BvhInstanceDesc{0, glm::mat4(1.0f)}});
  MESSAGE("one bunny: " << bunny.size() << " triangles, " << one.bytes() + one.triangles.size() * kShadingBytes
                        << " device bytes");
  CHECK(one.triangles.size() >= bunny.size());
}

TEST_CASE("bvh instances: ten thousand bunnies hold under twice one bunny's bytes" * doctest::test_suite("cpu shared-scenes slow")) {
  const std::string path = montecl_test::sharedScenes() + "/bunny/bunny.obj";
  MCL_SKIP_UNLESS(std::ifstream(path), path << " not found (the shared scenes are not beside this checkout)");
  const std::vector<SceneTriangle> bunny = bunnyTriangles(path);
  const TwoLevelBvh one = buildTwoLevelBvh({bunny}, {BvhInstanceDesc{0, glm::mat4(1.0f)}});
  std::vector<BvhInstanceDesc> grid;
  for (int k = 0; k < 10000; ++k) {  // a 100 x 100 grid, each turned and scaled a little
    glm::mat4 m = glm::translate(glm::mat4(1.0f), vec3(0.3f * float(k % 100), 0.0f, 0.3f * float(k / 100)));
    m = glm::rotate(m, 0.001f * float(k), vec3(0.0f, 1.0f, 0.0f));
    grid.push_back({0, glm::scale(m, vec3(1.0f + 0.00005f * float(k)))});
  }
  const TwoLevelBvh many = buildTwoLevelBvh({bunny}, grid);
  const std::size_t oneBytes = one.bytes() + one.triangles.size() * kShadingBytes;
  const std::size_t manyBytes = many.bytes() + many.triangles.size() * kShadingBytes;
  MESSAGE("10,000 bunnies: " << manyBytes << " device bytes (one: " << oneBytes << "; flattened copies: "
                             << double(oneBytes) * 10000.0 / 1e9 << " GB)");
  CHECK(many.triangles.size() == one.triangles.size());
  CHECK(manyBytes < 2 * oneBytes);
  // A ray down onto the grid's middle row meets a bunny.
  const TwoLevelHit h = intersectClosest(many, vec3(15.0f, 10.0f, 15.0f), vec3(0.0f, -1.0f, 0.0f), INFINITY);
  CHECK(h.instance != MCL_NO_INSTANCE);
}

TEST_CASE("bvh instances: the scene view maps every slot to its scene triangle" * doctest::test_suite("cpu")) {
  // One scene triangle list holding two meshes (object space) one after the other.
  std::vector<SceneTriangle> scene = montecl_test::seededSoup(150, 51, 3.0f, 1.0f, 0.2f);
  for (std::size_t i = 0; i < scene.size(); ++i) {
    scene[i].attributes = kHasUv;
    for (int k = 0; k < 3; ++k) scene[i].uv[k] = glm::vec2(float(i), float(k));
  }
  const std::vector<std::vector<SceneTriangle>> meshes = {{scene.begin(), scene.begin() + 100},
                                                          {scene.begin() + 100, scene.end()}};
  const TwoLevelBvh two = buildTwoLevelBvh(meshes, {{1, glm::scale(glm::mat4(1.0f), vec3(2.0f))}, {0, glm::mat4(1.0f)}});
  const Bvh view = sceneView(two, {0, 100});
  REQUIRE(view.order.size() == view.triangles.size());
  std::vector<int> seen(scene.size(), 0);
  for (std::size_t i = 0; i < view.triangles.size(); ++i) {
    const SceneTriangle& t = scene[view.order[i]];
    CAPTURE(i);
    CHECK(vec3(view.triangles[i].v0) == t.v[0]);
    CHECK(vec3(view.triangles[i].e1) == t.v[1] - t.v[0]);
    seen[view.order[i]] += as_uint(view.triangles[i].e1.w) == i;
  }
  CHECK(std::count(seen.begin(), seen.end(), 1) == int(scene.size()));  // every triangle's canonical slot once
  CHECK(view.inputCount == scene.size());
  REQUIRE(view.wideNodes().size() == two.nodes.size());
  CHECK(std::memcmp(view.wideNodes().data(), two.nodes.data(), two.nodes.size() * sizeof(WideNode)) == 0);
  // The per-triangle arrays built over the view follow the slots.
  const std::vector<TriangleShading> shading = buildTriangleShading(scene, view);
  REQUIRE(shading.size() == view.triangles.size());
  for (std::size_t i = 0; i < shading.size(); ++i) CHECK(shading[i].n0.w == float(view.order[i]));
}

}  // namespace test_file_bvh_instances
