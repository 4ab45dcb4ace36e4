// test_bvh_layouts.cpp: the wide (Bvh::wideNodes()) and binary (Bvh::nodes) host traversals find the same
// hits on random soups, a depth-capped tree and the shared scenes; and --bvh-layout's names and auto
// choice. (The kernels of both layouts: test_ray_tracer.cpp.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_internal.h"
#include "bvh/bvh_layout.h"
#include "kernels/shared/geometry.h"
#include "render/ray_tracer.h"
#include "cl/devices.h"
#include "render/stage_program.h"
#include "scene/scene.h"
#include "soups.h"
#include "util/errors.h"
#include "skip.h"

namespace test_file_bvh_layouts {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

std::vector<SceneTriangle> soup(int n, uint seed, float size) {
  return seededSoup(n, seed, 10.0f * size, size, 0.05f * size);
}

// Rays from inside [lo, hi], some axis-parallel, half with a finite tmax.
std::vector<Ray> rays(int n, uint seed, glm::vec3 lo, glm::vec3 hi) {
  return seededRays(n, seed, lo, hi, 0.05f, glm::length(hi - lo));
}

// Two different triangles hit at distances at most 2 ulps apart, each the distance its own
// triangle gives: coincident coplanar faces (the Cornell box's short-box bottom lies in the floor
// plane). The wide layout's conservative box distances may then skip the node of the hit that is
// 1 ulp closer; both hits are on the surface. Counted, and must stay rare.
bool coincidentTie(const Bvh& bvh, const Ray& r, const Hit& a, const Hit& b) {
  if (a.tri == MCL_NO_HIT || b.tri == MCL_NO_HIT || a.tri == b.tri) return false;
  if (std::fabs(a.t - b.t) > 2.0f * (std::nextafter(std::max(a.t, b.t), INFINITY) - std::max(a.t, b.t))) return false;
  for (const Hit* h : {&a, &b}) {
    const Triangle& t = bvh.triangles[h->tri];
    float u, v;
    if (!sameBits(ray_triangle(xyz(r.origin), xyz(r.dir), xyz(t.v0), xyz(t.e1), xyz(t.e2), INFINITY, &u, &v), h->t))
      return false;
  }
  return true;
}

// Host wide vs host binary traversal on every ray; returns the number of closest hits.
int checkHostLayouts(const Bvh& bvh, const std::vector<Ray>& rs) {
  int hits = 0, bad = 0, ties = 0;
  for (std::size_t i = 0; i < rs.size(); ++i) {
    glm::vec3 o = xyz(rs[i].origin), d = xyz(rs[i].dir);
    float tmax = rs[i].dir.w;
    Hit w = intersectClosest(bvh, o, d, tmax, BvhLayout::Wide);
    Hit b = intersectClosest(bvh, o, d, tmax, BvhLayout::Binary);
    bool anyW = intersectAny(bvh, o, d, tmax, BvhLayout::Wide);
    bool anyB = intersectAny(bvh, o, d, tmax, BvhLayout::Binary);
    bool same = sameHit(bvh, rs[i], w, b);
    if (!same && coincidentTie(bvh, rs[i], w, b)) {
      same = true;
      ++ties;
    }
    bool ok = same && anyW == anyB && anyW == (w.tri != MCL_NO_HIT);
    hits += w.tri != MCL_NO_HIT;
    if (!ok && bad++ < 5)
      MESSAGE("ray " << i << ": wide t " << w.t << " tri " << w.tri << " any " << anyW << ", binary t " << b.t
                     << " tri " << b.tri << " any " << anyB);
  }
  CHECK(bad == 0);
  CHECK(ties * 1000 <= int(rs.size()));  // rare: only rays meeting coincident coplanar faces
  if (ties) MESSAGE(ties << " rays tied within 2 ulps on coincident triangles");
  return hits;
}

}  // namespace

TEST_CASE("bvh layouts: wide and binary traversals give the same hits on the host" * doctest::test_suite("cpu")) {
  for (int n : {1, 5, 300, 5000}) {
    CAPTURE(n);
    std::vector<SceneTriangle> tris = soup(n, 11u + uint(n), n > 1000 ? 0.2f : 1.0f);
    Bvh bvh = buildBvh(tris);
    int hits = checkHostLayouts(bvh, rays(20000, 3u + uint(n), glm::vec3(-6.0f), glm::vec3(6.0f)));
    CHECK(hits > 0);
    CHECK(hits < 20000);
  }
  // A deep tree (depth capped at the limit): the binary traversal's stack holds one entry a level.
  std::vector<SceneTriangle> squares;
  for (int i = 0; i < 40; ++i) {
    float s = std::ldexp(1.0f, i - 20);
    squares.push_back({{glm::vec3(-s, -s, float(i) * 0.01f), glm::vec3(s, -s, float(i) * 0.01f),
                        glm::vec3(s, s, float(i) * 0.01f)}, 0});
  }
  Bvh deep = buildBvhCapped(squares, BvhBuildOptions{}, MCL_BVH_STACK_SIZE - 1);
  checkHostLayouts(deep, rays(5000, 5u, glm::vec3(-2.0f), glm::vec3(2.0f)));
}

TEST_CASE("bvh layouts: wide and binary traversals give the same hits on the shared scenes" * doctest::test_suite("cpu shared-scenes")) {
  MCL_SKIP_UNLESS(std::ifstream(sharedScenes() + "/cornell-box/scene.json"),
                  "no shared scenes at " << sharedScenes());
  int scenes = 0;
  for (const char* name : {"cornell-box", "bunny", "sibenik"}) {
    std::string path = sharedScenes() + "/" + name + "/scene.json";
    if (!std::ifstream(path)) continue;
    std::string sceneName = name;
    CAPTURE(sceneName);
    std::vector<std::string> warnings;
    Scene scene = loadScene(path, warnings);
    Bvh bvh = buildBvh(scene.triangles);
    glm::vec3 ext = scene.boundsMax - scene.boundsMin;
    int hits = checkHostLayouts(bvh, rays(20000, 9u, scene.boundsMin + 0.05f * ext, scene.boundsMax - 0.05f * ext));
    CHECK(hits > 1000);
    ++scenes;
  }
  CHECK(scenes > 0);
}

TEST_CASE("bvh layouts: wide node arrays start on 32 bytes, so no box row straddles a cache line" * doctest::test_suite("cpu")) {
  // CPU devices read the host's node array in place (CL_MEM_USE_HOST_PTR): each 32-byte row of
  // child bounds must lie in one cache line, which needs the array itself 32-byte aligned.
  for (int n : {1, 300, 5000}) {
    CAPTURE(n);
    Bvh bvh = buildBvh(soup(n, 7u + uint(n), 1.0f));
    const std::vector<WideNode>& wide = bvh.wideNodes();
    REQUIRE(!wide.empty());
    CHECK(reinterpret_cast<std::uintptr_t>(wide.data()) % 32 == 0);
  }
  // Arrays of many sizes, all alive at once (malloc's 16-byte alignment would leave some of them
  // 16 bytes off).
  std::vector<std::vector<WideNode>> arrays;
  for (std::size_t k = 1; k <= 40; ++k) arrays.emplace_back(k * 37 + k % 3);
  for (const std::vector<WideNode>& a : arrays) CHECK(reinterpret_cast<std::uintptr_t>(a.data()) % 32 == 0);
}

TEST_CASE("bvh layouts: names and the auto choice" * doctest::test_suite("cpu")) {
  CHECK(parseBvhLayout("auto") == BvhLayout::Auto);
  CHECK(parseBvhLayout("wide") == BvhLayout::Wide);
  CHECK(parseBvhLayout("binary") == BvhLayout::Binary);
  CHECK_THROWS_AS(parseBvhLayout("quad"), InputError);
  CHECK(std::string(bvhLayoutName(BvhLayout::Binary)) == "binary");
  CHECK(resolveBvhLayout(BvhLayout::Auto, true) == BvhLayout::Binary);
  CHECK(resolveBvhLayout(BvhLayout::Auto, false) == BvhLayout::Wide);
  CHECK(resolveBvhLayout(BvhLayout::Wide, true) == BvhLayout::Wide);
  CHECK(resolveBvhLayout(BvhLayout::Binary, false) == BvhLayout::Binary);
  CHECK(stageBuildOptions(BvhLayout::Binary).find("-DMCL_BVH_BINARY") != std::string::npos);
  CHECK(stageBuildOptions(BvhLayout::Wide).find("MCL_BVH_BINARY") == std::string::npos);
}

TEST_CASE("bvh layouts: the host backend traverses the wide layout only (the one layout rule)" *
          doctest::test_suite("cpu")) {
  const DeviceInfo host = selectDevice("host");
  CHECK(resolveStageLayout(BvhLayout::Auto, host) == BvhLayout::Wide);
  CHECK(resolveStageLayout(BvhLayout::Wide, host) == BvhLayout::Wide);
  CHECK_THROWS_AS(resolveStageLayout(BvhLayout::Binary, host), InputError);
  DeviceInfo gpu;
  gpu.isGpu = true;
  CHECK(resolveStageLayout(BvhLayout::Auto, gpu) == BvhLayout::Binary);
  CHECK(resolveStageLayout(BvhLayout::Wide, gpu) == BvhLayout::Wide);
}

// Non-finite rays must be misses, not crashes: a NaN ray "entered" every child through the NaN-dropping slab test,
// and an empty wide slot (0xffffffff, leaf bit set) was read as a leaf with a huge first index:
// without the fix this case dies with SIGSEGV in wide_closest_hit (ray_triangle4).
TEST_CASE("bvh layouts: a ray with a NaN or infinite origin or direction is a miss in both layouts" * doctest::test_suite("cpu")) {
  Bvh bvh = buildBvh(soup(300, 7u, 1.0f));
  const float nan = std::nanf(""), inf = INFINITY;
  const glm::vec3 origins[] = {{0, 0, -8}, {nan, 0, -8}, {0, inf, -8}, {-inf, 0, 0}};
  const glm::vec3 dirs[] = {{0, 0, 1}, {0, nan, 1}, {inf, 0, 1}, {nan, nan, nan}, {0, 0, -inf}};
  int cases = 0;
  for (const glm::vec3& o : origins)
    for (const glm::vec3& d : dirs) {
      if (o == origins[0] && d == dirs[0]) continue;  // the finite ray
      for (BvhLayout layout : {BvhLayout::Wide, BvhLayout::Binary}) {
        CAPTURE(int(layout));
        CAPTURE(++cases);
        for (float tmax : {INFINITY, 100.0f}) {
          Hit h = intersectClosest(bvh, o, d, tmax, layout);
          CHECK(h.tri == MCL_NO_HIT);
          CHECK(h.t == INFINITY);
          CHECK_FALSE(intersectAny(bvh, o, d, tmax, layout));
        }
      }
    }
  CHECK(ray_is_finite(glm::vec3(0, 0, -8), glm::vec3(0, 0, 1)));
  CHECK(ray_is_finite(glm::vec3(3e38f), glm::vec3(-3e38f)));
  CHECK_FALSE(ray_is_finite(glm::vec3(0, 0, nan), glm::vec3(0, 0, 1)));
  CHECK_FALSE(ray_is_finite(glm::vec3(0), glm::vec3(0, -inf, 1)));
}

// Whatever the ray and whatever an empty slot's box, the wide traversal never reads triangles
// through an empty slot: here every empty slot's box is made to cover everything (so finite rays
// enter them) and the hits must not change. Without the guard this reads tris[0x7ffffff] (SIGSEGV
// or garbage hits).
TEST_CASE("bvh layouts: the wide traversal never reads an empty slot, whatever its box" * doctest::test_suite("cpu")) {
  Bvh bvh = buildBvh(soup(300, 9u, 1.0f));
  Bvh broken = bvh;
  int emptySlots = 0;
  // The test edits the collapsed nodes in place (its own copy: a copied Bvh collapses anew).
  auto& brokenWide = const_cast<std::vector<WideNode>&>(broken.wideNodes());
  for (WideNode& n : brokenWide)
    for (int i = 0; i < MCL_WIDE_WIDTH; ++i)
      if (n.child[i] == MCL_WIDE_EMPTY) {
        ++emptySlots;
        for (int row = 0; row < 6; ++row) n.bounds[row][i] = row % 2 == 0 ? -1e30f : 1e30f;
      }
  REQUIRE(emptySlots > 0);
  std::vector<Ray> rs = rays(3000, 10u, glm::vec3(-6.0f), glm::vec3(6.0f));
  int bad = 0;
  for (const Ray& r : rs) {
    const glm::vec3 o = xyz(r.origin), d = xyz(r.dir);
    Hit a = intersectClosest(bvh, o, d, r.dir.w), b = intersectClosest(broken, o, d, r.dir.w);
    bad += a.tri != b.tri || !(a.t == b.t) ||
           intersectAny(bvh, o, d, r.dir.w) != intersectAny(broken, o, d, r.dir.w);
  }
  CHECK(bad == 0);
}

}  // namespace test_file_bvh_layouts
