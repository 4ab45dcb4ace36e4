// test_ray_tracer.cpp: the intersect and intersect_shadow kernels on the default OpenCL device
// against brute force over every triangle, on random soups and on a real mesh.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "kernels/shared/geometry.h"
#include "kernels/shared/rng.h"
#include "render/ray_tracer.h"
#include "scene/scene.h"

using namespace montecl;

namespace {

std::vector<SceneTriangle> randomSoup(int n, uint seed) {
  std::vector<SceneTriangle> tris;
  for (int i = 0; i < n; ++i) {
    float4 a = rng_uniform4(seed, uint(i), 0, 0), b = rng_uniform4(seed, uint(i), 0, 1),
           c = rng_uniform4(seed, uint(i), 0, 2);
    glm::vec3 center = glm::vec3(a.x, a.y, a.z) * 10.0f - 5.0f;
    float size = (i % 10 == 0) ? 3.0f : 0.3f * a.w + 0.01f;
    tris.push_back({{center, center + (glm::vec3(b.x, b.y, b.z) - 0.5f) * size,
                     center + (glm::vec3(c.x, c.y, c.z) - 0.5f) * size},
                    0});
  }
  return tris;
}

std::vector<Ray> randomRays(int n, uint seed, glm::vec3 lo, glm::vec3 hi) {
  std::vector<Ray> rays(n);
  for (int i = 0; i < n; ++i) {
    float4 a = rng_uniform4(seed, uint(i), 1, 0), b = rng_uniform4(seed, uint(i), 1, 1);
    glm::vec3 o = lo + (hi - lo) * glm::vec3(a.x, a.y, a.z);
    glm::vec3 d = glm::normalize(glm::vec3(b.x, b.y, b.z) - 0.5f);
    if (i % 7 == 0) d = glm::vec3(i % 3 == 0, i % 3 == 1, i % 3 == 2) * (b.w < 0.5f ? 1.0f : -1.0f);
    float tmax = (i % 2) ? INFINITY : 0.5f + 4.0f * a.w;
    rays[i].origin = glm::vec4(o, 0.0f);
    rays[i].dir = glm::vec4(d, tmax);
  }
  return rays;
}

// Brute-force closest t over the input triangles.
float bruteClosest(const std::vector<SceneTriangle>& tris, const Ray& r) {
  float best = r.dir.w;
  for (const auto& t : tris) {
    float u, v;
    float h = ray_triangle(xyz(r.origin), xyz(r.dir), t.v[0], t.v[1] - t.v[0], t.v[2] - t.v[0], best, &u, &v);
    if (h < best) best = h;
  }
  return best < r.dir.w ? best : INFINITY;
}

void checkAgainstBruteForce(const std::vector<SceneTriangle>& tris, const std::vector<Ray>& rays,
                            double minHitFraction = 0.02) {
  static const DeviceInfo device = selectDevice("");
  static ClSession session(device);
  Bvh bvh = buildBvh(tris);
  RayTracer tracer(session, bvh);
  std::vector<Hit> hits = tracer.closest(rays);
  std::vector<int> occ = tracer.occluded(rays);
  int hitCount = 0, mismatches = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    float expected = bruteClosest(tris, rays[i]);
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

TEST_CASE("OpenCL closest-hit and any-hit equal brute force on random soups") {
  checkAgainstBruteForce(randomSoup(1, 1), randomRays(20000, 2, glm::vec3(-6), glm::vec3(6)), 1e-4);
  checkAgainstBruteForce(randomSoup(300, 3), randomRays(50000, 4, glm::vec3(-6), glm::vec3(6)));
  checkAgainstBruteForce(randomSoup(3000, 5), randomRays(50000, 6, glm::vec3(-6), glm::vec3(6)));
}

TEST_CASE("OpenCL closest-hit and any-hit equal brute force on the Stanford bunny") {
  std::string path = std::string(MONTECL_SHARED_SCENES) + "/bunny/scene.json";
  if (!std::ifstream(path)) {
    MESSAGE("skipping: " << path << " not found (the shared scenes are not beside this checkout)");
    return;
  }
  std::vector<std::string> warnings;
  Scene scene = loadScene(path, warnings);
  // Rays from around the bunny's bounds; brute force over 69k triangles, so keep the count modest.
  glm::vec3 ext = scene.boundsMax - scene.boundsMin;
  checkAgainstBruteForce(scene.triangles,
                         randomRays(3000, 7, scene.boundsMin - 0.2f * ext, scene.boundsMax + 0.2f * ext));
}
