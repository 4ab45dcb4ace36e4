// test_bvh_layouts.cpp: the wide (Bvh::wide) and binary (Bvh::nodes) traversals find the same hits,
// on the host and in the kernels of both layouts, on random soups, a depth-capped tree and the
// shared scenes; and --bvh-layout's names and auto choice.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_internal.h"
#include "bvh/bvh_layout.h"
#include "cl/devices.h"
#include "kernels/shared/geometry.h"
#include "kernels/shared/rng.h"
#include "render/ray_tracer.h"
#include "scene/scene.h"
#include "util/errors.h"

using namespace montecl;

namespace {

std::vector<SceneTriangle> soup(int n, uint seed, float size) {
  std::vector<SceneTriangle> tris;
  for (int i = 0; i < n; ++i) {
    float4 a = rng_uniform4(seed, uint(i), 0, 0), b = rng_uniform4(seed, uint(i), 0, 1),
           c = rng_uniform4(seed, uint(i), 0, 2);
    glm::vec3 p = glm::vec3(a.x, a.y, a.z) * 10.0f - 5.0f;
    float s = (i % 10 == 0) ? 10.0f * size : size * (a.w + 0.05f);
    tris.push_back({{p, p + (glm::vec3(b.x, b.y, b.z) - 0.5f) * s, p + (glm::vec3(c.x, c.y, c.z) - 0.5f) * s}, 0});
  }
  return tris;
}

// Rays from inside [lo, hi], some axis-parallel, half with a finite tmax.
std::vector<Ray> rays(int n, uint seed, glm::vec3 lo, glm::vec3 hi) {
  std::vector<Ray> out(n);
  for (int i = 0; i < n; ++i) {
    float4 a = rng_uniform4(seed, uint(i), 1, 0), b = rng_uniform4(seed, uint(i), 1, 1);
    glm::vec3 d = glm::normalize(glm::vec3(b.x, b.y, b.z) - 0.5f);
    if (i % 7 == 0) d = glm::vec3(i % 3 == 0, i % 3 == 1, i % 3 == 2) * (b.w < 0.5f ? 1.0f : -1.0f);
    float tmax = (i % 2) ? INFINITY : 0.05f + glm::length(hi - lo) * a.w;
    out[i].origin = glm::vec4(lo + (hi - lo) * glm::vec3(a.x, a.y, a.z), 0.0f);
    out[i].dir = glm::vec4(d, tmax);
  }
  return out;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Two closest hits agree: same t to the bit, and the same triangle and barycentrics, or (a tie)
// another triangle that the ray meets at exactly that t.
bool sameHit(const Bvh& bvh, const Ray& r, const Hit& a, const Hit& b) {
  if (!sameBits(a.t, b.t) || (a.tri == MCL_NO_HIT) != (b.tri == MCL_NO_HIT)) return false;
  if (a.tri == b.tri) return sameBits(a.u, b.u) && sameBits(a.v, b.v);
  const Triangle& t = bvh.triangles[b.tri];
  float u, v;
  float tb = ray_triangle(xyz(r.origin), xyz(r.dir), xyz(t.v0), xyz(t.e1), xyz(t.e2), INFINITY, &u, &v);
  return sameBits(tb, a.t);
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

TEST_CASE("bvh layouts: wide and binary traversals give the same hits on the host") {
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

TEST_CASE("bvh layouts: wide and binary traversals give the same hits on the shared scenes") {
  int scenes = 0;
  for (const char* name : {"cornell-box", "bunny", "sibenik"}) {
    std::string path = std::string(MONTECL_SHARED_SCENES) + "/" + name + "/scene.json";
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
  if (scenes == 0) MESSAGE("skipping: no shared scenes at " << MONTECL_SHARED_SCENES);
}

TEST_CASE("bvh layouts: the binary kernels equal the wide kernels and the host reference") {
  const DeviceInfo device = selectDevice("");
  StageProgram wideSession(device, BvhLayout::Wide);
  StageProgram binarySession(device, BvhLayout::Binary);
  CHECK(wideSession.layout() == BvhLayout::Wide);
  CHECK(binarySession.layout() == BvhLayout::Binary);
  std::vector<SceneTriangle> tris = soup(3000, 21u, 0.3f);
  Bvh bvh = buildBvh(tris);
  std::vector<Ray> rs = rays(30000, 22u, glm::vec3(-6.0f), glm::vec3(6.0f));
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

TEST_CASE("bvh layouts: names and the auto choice") {
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

TEST_CASE("bvh layouts: the host backend traverses the wide layout only (the one layout rule)") {
  const DeviceInfo host = selectDevice("host");
  CHECK(resolveStageLayout(BvhLayout::Auto, host) == BvhLayout::Wide);
  CHECK(resolveStageLayout(BvhLayout::Wide, host) == BvhLayout::Wide);
  CHECK_THROWS_AS(resolveStageLayout(BvhLayout::Binary, host), InputError);
  DeviceInfo gpu;
  gpu.isGpu = true;
  CHECK(resolveStageLayout(BvhLayout::Auto, gpu) == BvhLayout::Binary);
  CHECK(resolveStageLayout(BvhLayout::Wide, gpu) == BvhLayout::Wide);
}
