// test_bvh_layouts.cpp: the wide (Bvh::wide) and binary (Bvh::nodes) host traversals find the same
// hits on random soups, a depth-capped tree and the shared scenes; and --bvh-layout's names and auto
// choice. (The kernels of both layouts: test_ray_tracer.cpp.)
#include <doctest/doctest.h>

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

// Host wide vs host binary traversal on every ray; returns the number of closest hits.
int checkHostLayouts(const Bvh& bvh, const std::vector<Ray>& rs) {
  int hits = 0, bad = 0;
  for (std::size_t i = 0; i < rs.size(); ++i) {
    glm::vec3 o = xyz(rs[i].origin), d = xyz(rs[i].dir);
    float tmax = rs[i].dir.w;
    Hit w = intersectClosest(bvh, o, d, tmax, BvhLayout::Wide);
    Hit b = intersectClosest(bvh, o, d, tmax, BvhLayout::Binary);
    bool anyW = intersectAny(bvh, o, d, tmax, BvhLayout::Wide);
    bool anyB = intersectAny(bvh, o, d, tmax, BvhLayout::Binary);
    bool ok = sameHit(bvh, rs[i], w, b) && anyW == anyB && anyW == (w.tri != MCL_NO_HIT);
    hits += w.tri != MCL_NO_HIT;
    if (!ok && bad++ < 5)
      MESSAGE("ray " << i << ": wide t " << w.t << " tri " << w.tri << " any " << anyW << ", binary t " << b.t
                     << " tri " << b.tri << " any " << anyB);
  }
  CHECK(bad == 0);
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
