// test_ray_tracer.cpp: host/render/ray_tracer: the intersect and intersect_shadow kernels on the
// default OpenCL device against brute force over every triangle, on random soups and on a real
// mesh (also in packets of rays from about one point, and with every packet through the packet
// traversals), the binary-layout kernels against the wide-layout kernels and the host traversal,
// and the hit every traversal keeps among triangles at exactly the same t.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_layout.h"
#include "cl/devices.h"
#include "kernels/shared/geometry.h"
#include "render/ray_tracer.h"
#include "scene/scene.h"
#include "soups.h"
#include "skip.h"

namespace test_file_ray_tracer {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

std::vector<SceneTriangle> randomSoup(int n, uint seed) { return seededSoup(n, seed, 3.0f, 0.3f, 0.01f); }

std::vector<Ray> randomRays(int n, uint seed, glm::vec3 lo, glm::vec3 hi) {
  return seededRays(n, seed, lo, hi, 0.5f, 4.0f);
}

// Runs of 16 rays (the widest packet) leaving from about one point in about one direction, as one
// pixel's camera rays or its samples' shadow rays towards a light: most runs share an octant.
std::vector<Ray> packetRays(int n, uint seed, glm::vec3 lo, glm::vec3 hi) {
  std::vector<Ray> rays = randomRays(n, seed, lo, hi);
  for (int i = 0; i < n; ++i) {
    const Ray& lead = rays[std::size_t(i - i % 16)];
    if (i % 16 == 0) continue;
    glm::vec3 o = glm::vec3(lead.origin) + 0.01f * glm::vec3(rays[i].origin);
    glm::vec3 d = glm::normalize(glm::vec3(lead.dir) + 0.1f * glm::vec3(rays[i].dir));
    rays[i].origin = glm::vec4(o, 0.0f);
    rays[i].dir = glm::vec4(d, rays[i].dir.w);
  }
  return rays;
}

void checkAgainstBruteForce(const std::vector<SceneTriangle>& tris, const std::vector<Ray>& rays,
                            double minHitFraction = 0.02, bool packetAllRays = false) {
  static const DeviceInfo device = selectDevice("");
  static StageProgram program(device);
  Bvh bvh = buildBvh(tris);
  RayTracer tracer(program, bvh);
  tracer.setPacketAllRays(packetAllRays);
  std::vector<Hit> hits = tracer.closest(rays);
  std::vector<int> occ = tracer.occluded(rays);
  int hitCount = 0, mismatches = 0;
  BruteForce brute(tris);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    float expected = brute.closest(xyz(rays[i].origin), xyz(rays[i].dir), rays[i].dir.w).t;
    bool expectHit = expected != INFINITY;
    hitCount += expectHit;
    bool ok = (hits[i].tri != MCL_NO_HIT) == expectHit && occ[i] == int(expectHit);
    if (ok && expectHit) ok = std::fabs(hits[i].t - expected) <= 1e-5f * std::max(1.0f, expected);
    if (!ok && mismatches++ < 5)
      MESSAGE("ray " << i << ": expected t " << expected << ", kernel t " << hits[i].t << " tri " << hits[i].tri
                     << " occluded " << occ[i]);
  }
  CHECK(mismatches == 0);
  CHECK(hitCount > minHitFraction * rays.size());  // the rays do hit things
  CHECK(hitCount < int(rays.size()));       // and miss some
}

}  // namespace

TEST_CASE("OpenCL closest-hit and any-hit equal brute force on random soups" * doctest::test_suite("opencl")) {
  checkAgainstBruteForce(randomSoup(1, 1), randomRays(20000, 2, glm::vec3(-6), glm::vec3(6)), 1e-4);
  checkAgainstBruteForce(randomSoup(300, 3), randomRays(50000, 4, glm::vec3(-6), glm::vec3(6)));
  checkAgainstBruteForce(randomSoup(3000, 5), randomRays(50000, 6, glm::vec3(-6), glm::vec3(6)));
}

TEST_CASE("OpenCL packet traversals (closest and any hit) equal brute force on random soups" *
          doctest::test_suite("opencl")) {
  // Packets of rays from about one point (one octant: the packet traversals' coherent case) ...
  checkAgainstBruteForce(randomSoup(300, 3), packetRays(50000, 8, glm::vec3(-6), glm::vec3(6)));
  checkAgainstBruteForce(randomSoup(3000, 5), packetRays(50000, 9, glm::vec3(-6), glm::vec3(6)));
  // ... and rays in every direction with every packet through them, as renders of small trees run.
  checkAgainstBruteForce(randomSoup(300, 10), randomRays(50000, 11, glm::vec3(-6), glm::vec3(6)), 0.02, true);
  checkAgainstBruteForce(randomSoup(3000, 5), randomRays(50000, 6, glm::vec3(-6), glm::vec3(6)), 0.02, true);
}

// Every triangle three times over (exact copies, scattered through the input): a ray that hits
// meets three triangles at exactly the same t, and every closest-hit traversal (single rays and
// packets, both layouts, on the device and on the host) keeps the copy with the lowest canonical
// slot, whatever order it visits them in.
TEST_CASE("closest hit at an equal t: every traversal keeps the lowest canonical slot" * doctest::test_suite("opencl")) {
  const std::size_t n = 300;
  std::vector<SceneTriangle> base = randomSoup(int(n), 31), tris;
  std::vector<std::size_t> baseOf;
  for (std::size_t copy = 0; copy < 3; ++copy)
    for (std::size_t i = 0; i < n; ++i) {
      baseOf.push_back((i * 7 + copy * 101) % n);  // 7 is prime to 300: each copy a permutation
      tris.push_back(base[baseOf.back()]);
    }
  Bvh bvh = buildBvh(tris);
  // The lowest canonical slot among each base triangle's copies (a canonical slot: the first leaf
  // slot of an input triangle).
  std::vector<std::uint32_t> firstSlot(tris.size(), MCL_NO_HIT), lowest(n, MCL_NO_HIT);
  for (std::size_t s = bvh.order.size(); s-- > 0;) firstSlot[bvh.order[s]] = std::uint32_t(s);
  for (std::size_t j = 0; j < tris.size(); ++j) lowest[baseOf[j]] = std::min(lowest[baseOf[j]], firstSlot[j]);

  const DeviceInfo device = selectDevice("");
  StageProgram wideSession(device, BvhLayout::Wide), binarySession(device, BvhLayout::Binary);
  RayTracer wide(wideSession, bvh), binary(binarySession, bvh);
  BruteForce brute(tris);
  for (int pass = 0; pass < 2; ++pass) {
    // Runs of rays from about one point (packets in one octant), then rays in every direction with
    // every packet through the packet traversal.
    std::vector<Ray> rays = pass == 0 ? packetRays(20000, 32, glm::vec3(-6), glm::vec3(6))
                                      : randomRays(20000, 33, glm::vec3(-6), glm::vec3(6));
    wide.setPacketAllRays(pass == 1);
    std::vector<Hit> hw = wide.closest(rays), hb = binary.closest(rays);
    int hits = 0, bad = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const glm::vec3 o = xyz(rays[i].origin), d = xyz(rays[i].dir);
      RefHit ref = brute.closest(o, d, rays[i].dir.w);
      std::uint32_t expected = ref.tri == MCL_NO_HIT ? MCL_NO_HIT : lowest[baseOf[ref.tri]];
      hits += ref.tri != MCL_NO_HIT;
      Hit hostWide = intersectClosest(bvh, o, d, rays[i].dir.w, BvhLayout::Wide);
      Hit hostBinary = intersectClosest(bvh, o, d, rays[i].dir.w, BvhLayout::Binary);
      bool ok = hw[i].tri == expected && hb[i].tri == expected && hostWide.tri == expected &&
                hostBinary.tri == expected;
      if (!ok && bad++ < 5)
        MESSAGE("pass " << pass << " ray " << i << ": expected slot " << expected << ", wide kernel " << hw[i].tri
                        << ", binary kernel " << hb[i].tri << ", host wide " << hostWide.tri << ", host binary "
                        << hostBinary.tri);
    }
    CHECK(bad == 0);
    CHECK(hits > 300);  // the rays do meet the copies
  }
}

TEST_CASE("OpenCL closest-hit and any-hit equal brute force on the Stanford bunny" * doctest::test_suite("opencl shared-scenes")) {
  std::string path = sharedScenes() + "/bunny/scene.json";
  MCL_SKIP_UNLESS(std::ifstream(path), path << " not found (the shared scenes are not beside this checkout)");
  std::vector<std::string> warnings;
  Scene scene = loadScene(path, warnings);
  // Rays from around the bunny's bounds; brute force over 69k triangles, so keep the count modest.
  glm::vec3 ext = scene.boundsMax - scene.boundsMin;
  checkAgainstBruteForce(scene.triangles,
                         randomRays(3000, 7, scene.boundsMin - 0.2f * ext, scene.boundsMax + 0.2f * ext));
}

TEST_CASE("bvh layouts: the binary kernels equal the wide kernels and the host reference" * doctest::test_suite("opencl")) {
  const DeviceInfo device = selectDevice("");
  StageProgram wideSession(device, BvhLayout::Wide);
  StageProgram binarySession(device, BvhLayout::Binary);
  CHECK(wideSession.layout() == BvhLayout::Wide);
  CHECK(binarySession.layout() == BvhLayout::Binary);
  std::vector<SceneTriangle> tris = seededSoup(3000, 21u, 3.0f, 0.3f, 0.3f * 0.05f);
  Bvh bvh = buildBvh(tris);
  std::vector<Ray> rs = seededRays(30000, 22u, glm::vec3(-6.0f), glm::vec3(6.0f), 0.05f, glm::length(glm::vec3(12.0f)));
  RayTracer wide(wideSession, bvh), binary(binarySession, bvh);
  std::vector<Hit> hw = wide.closest(rs), hb = binary.closest(rs);
  std::vector<int> ow = wide.occluded(rs), ob = binary.occluded(rs);
  int bad = 0;
  for (std::size_t i = 0; i < rs.size(); ++i) {
    Hit ref = intersectClosest(bvh, xyz(rs[i].origin), xyz(rs[i].dir), rs[i].dir.w, BvhLayout::Binary);
    bool ok = sameHit(bvh, rs[i], hw[i], hb[i]) && hb[i].tri == ref.tri && sameBits(hb[i].t, ref.t) &&
              sameBits(hb[i].u, ref.u) && sameBits(hb[i].v, ref.v) && ow[i] == ob[i] &&
              ob[i] == int(ref.tri != MCL_NO_HIT);
    if (!ok && bad++ < 5)
      MESSAGE("ray " << i << ": wide kernel t " << hw[i].t << " tri " << hw[i].tri << ", binary kernel t " << hb[i].t
                     << " tri " << hb[i].tri << ", host binary t " << ref.t << " tri " << ref.tri);
  }
  CHECK(bad == 0);

  // An empty BVH (no triangles): one node no ray enters, in either layout.
  Bvh empty;
  RayTracer emptyBinary(binarySession, empty);
  std::vector<Hit> none = emptyBinary.closest(std::vector<Ray>(rs.begin(), rs.begin() + 100));
  for (const Hit& h : none) CHECK(h.tri == MCL_NO_HIT);
}

// Non-finite rays on the device, both layouts: misses, counted, their shadow light
// dropped, and the finite rays of the same launch unaffected. Without the fix the wide kernels
// read triangles through an empty slot (SIGSEGV inside PoCL) and nothing is counted.
TEST_CASE("OpenCL: rays with a NaN or infinite origin or direction are misses, counted, in both layouts" * doctest::test_suite("opencl")) {
  const DeviceInfo device = selectDevice("");
  std::vector<SceneTriangle> tris = seededSoup(2000, 31u, 3.0f, 0.3f, 0.015f);
  Bvh bvh = buildBvh(tris);
  std::vector<Ray> rs = seededRays(4000, 32u, glm::vec3(-4.0f), glm::vec3(4.0f), 0.5f, 8.0f);
  const float nan = std::nanf("");
  std::uint32_t poisoned = 0;
  for (std::size_t i = 0; i < rs.size(); i += 3, ++poisoned) {
    switch (i % 4) {  // i = 0, 3, 6, 9, ... mod 4 cycles through 0, 3, 2, 1
      case 0: rs[i].origin = glm::vec4(nan, nan, nan, 1.0f); break;  // enters every box
      case 1: rs[i].dir = glm::vec4(nan, nan, nan, rs[i].dir.w); break;
      case 2: rs[i].dir.x = -INFINITY; break;
      default: rs[i].origin.y = nan; break;
    }
  }
  for (BvhLayout layout : {BvhLayout::Wide, BvhLayout::Binary}) {
    CAPTURE(int(layout));
    StageProgram program(device, layout);
    RayTracer tracer(program, bvh);
    std::vector<Hit> hits = tracer.closest(rs);
    CHECK(tracer.nanRays() == poisoned);
    std::vector<int> occ = tracer.occluded(rs);
    CHECK(tracer.nanRays() == 2 * poisoned);
    int bad = 0, finiteHits = 0;
    for (std::size_t i = 0; i < rs.size(); ++i) {
      Hit ref = intersectClosest(bvh, xyz(rs[i].origin), xyz(rs[i].dir), rs[i].dir.w, layout);
      const bool poison = i % 3 == 0;
      finiteHits += !poison && ref.tri != MCL_NO_HIT;
      bad += hits[i].tri != ref.tri || !sameBits(hits[i].t, ref.t) ||
             occ[i] != (poison ? 1 : int(ref.tri != MCL_NO_HIT)) || (poison && ref.tri != MCL_NO_HIT);
    }
    CHECK(bad == 0);
    CHECK(finiteHits > 100);
  }
}

}  // namespace test_file_ray_tracer
