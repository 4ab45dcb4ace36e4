// test_bvh_spatial.cpp: spatial splits (host/bvh/bvh_spatial.h, bvh_sbvh.cpp). A reference split
// at a plane stays inside its box and, with its other half, covers the triangle; a tree built with
// spatial splits over long thin triangles does duplicate references (within the budget), every
// point of every triangle lies in a leaf that references it, both layouts' closest and any hit
// equal brute force and return canonical slots; the emitter table counts each triangle once; and
// a render with and without spatial splits is bit-identical.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_spatial.h"
#include "cl/devices.h"
#include "kernels/shared/geometry.h"
#include "render/emitters.h"
#include "render/wavefront.h"
#include "scene/builtin_scenes.h"
#include "soups.h"

namespace test_file_bvh_spatial {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl::bvhbuild;
using glm::vec3;

namespace {

float uni(std::mt19937& rng, float a, float b) {
  return std::uniform_real_distribution<float>(a, b)(rng);
}

vec3 randPoint(std::mt19937& rng, float s) { return vec3(uni(rng, -s, s), uni(rng, -s, s), uni(rng, -s, s)); }

// n triangles in [-5, 5]^3: every tenth a long thin one (length up to 2 * len, width up to
// ~0.2) at a random orientation, the others small (up to ~0.4 across): the case spatial splits
// are for (the long ones' boxes overlap everything near them; architecture's walls and floors).
std::vector<SceneTriangle> slivers(int n, std::uint32_t seed, float len, std::uint32_t materials = 1) {
  std::mt19937 rng(seed);
  std::vector<SceneTriangle> tris(n);
  for (int i = 0; i < n; ++i) {
    const bool longOne = i % 10 == 0;
    vec3 c = randPoint(rng, 5.0f), d = randPoint(rng, 1.0f) * (longOne ? len : 0.2f), w = randPoint(rng, 0.2f);
    SceneTriangle& t = tris[i];
    t.v[0] = c - d;
    t.v[1] = c + d;
    t.v[2] = c + w;
    t.material = std::uint32_t(i) % materials;
  }
  return tris;
}

// A point of t at barycentrics (1 - a - b, a, b).
vec3 pointOn(const SceneTriangle& t, float a, float b) {
  return t.v[0] * (1.0f - a - b) + t.v[1] * a + t.v[2] * b;
}

bool inside(vec3 p, vec3 lo, vec3 hi) {
  return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

// Spatial splits tried wherever the object split's children overlap at all (alpha 1e-5, the
// paper's; the default 1e-3 leaves these small scenes almost unsplit).
BvhBuildOptions withSplits(float budget) {
  BvhBuildOptions o;
  o.splitBudget = budget;
  o.splitAlpha = 1e-5f;
  return o;
}

}  // namespace

TEST_CASE("bvh spatial: a split reference stays in its box, and its halves cover the triangle" * doctest::test_suite("cpu")) {
  std::mt19937 rng(3);
  int splitBoth = 0;
  for (int iter = 0; iter < 2000; ++iter) {
    SceneTriangle t;
    for (vec3& v : t.v) v = randPoint(rng, 10.0f);
    PrimRef r{};
    r.lo = glm::min(glm::min(t.v[0], t.v[1]), t.v[2]);
    r.hi = glm::max(glm::max(t.v[0], t.v[1]), t.v[2]);
    r.id = 7;
    // Half the time a reference already clipped: a random sub-box of the triangle's box.
    if (iter % 2) {
      vec3 a = glm::mix(r.lo, r.hi, vec3(uni(rng, 0, 0.4f), uni(rng, 0, 0.4f), uni(rng, 0, 0.4f)));
      vec3 b = glm::mix(r.lo, r.hi, vec3(uni(rng, 0.6f, 1), uni(rng, 0.6f, 1), uni(rng, 0.6f, 1)));
      r.lo = a;
      r.hi = b;
    }
    int axis = iter % 3;
    float pos = uni(rng, r.lo[axis], r.hi[axis]);
    PrimRef l, h;
    splitReference(r, t, axis, pos, l, h);
    CAPTURE(iter);
    CHECK(l.id == 7u);
    CHECK(h.id == 7u);
    if (validRef(l)) {
      CHECK(inside(l.lo, r.lo, r.hi));
      CHECK(inside(l.hi, r.lo, r.hi));
      CHECK(l.hi[axis] <= pos);
    }
    if (validRef(h)) {
      CHECK(inside(h.lo, r.lo, r.hi));
      CHECK(inside(h.hi, r.lo, r.hi));
      CHECK(h.lo[axis] >= pos);
    }
    splitBoth += validRef(l) && validRef(h);
    // Every sampled point of the triangle inside r's box lies in one of the halves.
    int missed = 0;
    for (int k = 0; k < 200; ++k) {
      float a = uni(rng, 0, 1), b = uni(rng, 0, 1);
      if (a + b > 1.0f) { a = 1.0f - a; b = 1.0f - b; }
      vec3 p = pointOn(t, a, b);
      if (!inside(p, r.lo, r.hi)) continue;
      bool inL = validRef(l) && inside(p, l.lo, l.hi), inH = validRef(h) && inside(p, h.lo, h.hi);
      missed += !(inL || inH);
    }
    CHECK(missed == 0);
  }
  CHECK(splitBoth > 1000);  // not vacuous: most planes cut the triangle
}

TEST_CASE("bvh spatial: slivers get duplicated references within the budget, all covered by their leaves" * doctest::test_suite("cpu")) {
  std::vector<SceneTriangle> tris = slivers(3000, 11u, 2.0f);
  for (float budget : {0.05f, 0.3f, 1.0f}) {
    CAPTURE(budget);
    Bvh bvh = buildBvh(tris, withSplits(budget));
    const std::size_t n = tris.size(), m = bvh.triangles.size();
    REQUIRE(bvh.order.size() == m);
    CHECK(bvh.inputCount == n);
    CHECK(m > n);
    CHECK(m <= n + std::size_t(budget * float(n)));
    Bvh plain = buildBvh(tris, withSplits(0.0f));
    CHECK(plain.triangles.size() == n);
    CHECK(bvh.sahCost < plain.sahCost);
    MESSAGE("budget " << budget << ": " << m - n << " extra references, SAH " << bvh.sahCost
                      << " (object splits only " << plain.sahCost << ")");
    // Leaves over slots; each slot's leaf box. Canonical slot = first slot of the same triangle.
    std::vector<int> leafOf(m, -1);
    for (std::size_t k = 0; k < bvh.nodes.size(); ++k) {
      const BvhNode& nd = bvh.nodes[k];
      for (std::uint32_t i = nd.leftFirst; nd.triCount > 0 && i < nd.leftFirst + nd.triCount; ++i) {
        REQUIRE(i < m);
        CHECK(leafOf[i] == -1);
        leafOf[i] = int(k);
      }
    }
    std::vector<std::vector<std::uint32_t>> slots(n);
    for (std::size_t i = 0; i < m; ++i) {
      REQUIRE(leafOf[i] >= 0);
      REQUIRE(bvh.order[i] < n);
      slots[bvh.order[i]].push_back(std::uint32_t(i));
    }
    std::mt19937 rng(5);
    std::size_t uncovered = 0, badCanonical = 0, badBox = 0;
    for (std::size_t id = 0; id < n; ++id) {
      REQUIRE(!slots[id].empty());
      const SceneTriangle& t = tris[id];
      vec3 tlo = glm::min(glm::min(t.v[0], t.v[1]), t.v[2]), thi = glm::max(glm::max(t.v[0], t.v[1]), t.v[2]);
      for (std::uint32_t s : slots[id]) {
        badCanonical += as_uint(bvh.triangles[s].e1.w) != slots[id].front();
        const BvhNode& nd = bvh.nodes[leafOf[s]];
        // A leaf box holding only this triangle's part lies inside its box; in general the leaf
        // box is the union of its references' boxes, each inside its triangle's box.
        if (nd.triCount == 1) badBox += !(inside(vec3(nd.minX, nd.minY, nd.minZ), tlo, thi) &&
                                          inside(vec3(nd.maxX, nd.maxY, nd.maxZ), tlo, thi));
      }
      for (int k = 0; k < 64; ++k) {
        float a = uni(rng, 0, 1), b = uni(rng, 0, 1);
        if (a + b > 1.0f) { a = 1.0f - a; b = 1.0f - b; }
        if (k < 3) { a = k == 1 ? 1.0f : 0.0f; b = k == 2 ? 1.0f : 0.0f; }  // the corners too
        vec3 p = pointOn(t, a, b);
        bool in = false;
        for (std::uint32_t s : slots[id]) {
          const BvhNode& nd = bvh.nodes[leafOf[s]];
          in = in || inside(p, vec3(nd.minX, nd.minY, nd.minZ), vec3(nd.maxX, nd.maxY, nd.maxZ));
        }
        uncovered += !in;
      }
    }
    CHECK(uncovered == 0);
    CHECK(badCanonical == 0);
    CHECK(badBox == 0);
  }
}

TEST_CASE("bvh spatial: closest and any hit equal brute force on slivers, both layouts, canonical slots" * doctest::test_suite("cpu")) {
  for (std::uint32_t seed : {1u, 2u}) {
    std::vector<SceneTriangle> tris = slivers(2000, seed, seed == 1u ? 3.0f : 0.5f);
    Bvh bvh = buildBvh(tris, withSplits(0.5f));
    REQUIRE(bvh.triangles.size() > tris.size());
    montecl_test::BruteForce brute(tris);
    std::vector<Ray> rays = montecl_test::seededRays(4000, seed + 10u, vec3(-6.0f), vec3(6.0f), 0.5f, 8.0f);
    int hits = 0, ties = 0, bad = 0;
    std::string first;
    for (const Ray& r : rays) {
      vec3 o = xyz(r.origin), d = xyz(r.dir);
      float tmax = r.dir.w;
      montecl_test::RefHit ref = brute.closest(o, d, tmax);
      for (BvhLayout layout : {BvhLayout::Wide, BvhLayout::Binary}) {
        Hit h = intersectClosest(bvh, o, d, tmax, layout);
        bool any = intersectAny(bvh, o, d, tmax, layout);
        bool ok = (h.tri == MCL_NO_HIT) == (ref.tri == MCL_NO_HIT) && any == (ref.tri != MCL_NO_HIT);
        if (ok && h.tri != MCL_NO_HIT) {
          ok = h.tri < bvh.triangles.size() && as_uint(bvh.triangles[h.tri].e1.w) == h.tri &&
               montecl_test::sameBits(h.t, ref.t);
          if (ok && bvh.order[h.tri] != ref.tri) ++ties;
          if (layout == BvhLayout::Wide) ++hits;
        }
        if (!ok && bad++ == 0)
          first = "ray o=(" + std::to_string(o.x) + "," + std::to_string(o.y) + "," + std::to_string(o.z) +
                  ") t=" + std::to_string(h.t) + " ref t=" + std::to_string(ref.t);
      }
    }
    INFO(first);
    CHECK(bad == 0);
    CHECK(ties <= 2);
    CHECK(hits > 150);
    CHECK(hits < 4000);
  }
}

TEST_CASE("bvh spatial: the emitter table counts each triangle once" * doctest::test_suite("cpu")) {
  std::vector<SceneTriangle> tris = slivers(1500, 4u, 2.0f, 3);
  std::vector<MaterialDesc> materials{MaterialDesc("dark", vec3(0.5f)), MaterialDesc("lamp", vec3(0.5f), vec3(2, 3, 4)),
                                      MaterialDesc("dim", vec3(0.5f), vec3(0.5f))};
  Bvh plain = buildBvh(tris, withSplits(0.0f)), split = buildBvh(tris, withSplits(0.5f));
  REQUIRE(split.triangles.size() > plain.triangles.size());
  EmitterTable a = buildEmitterTable(plain, materials), b = buildEmitterTable(split, materials);
  REQUIRE(a.emitters.size() == 1000);  // materials 1 and 2
  REQUIRE(b.emitters.size() == a.emitters.size());
  CHECK(b.totalPower == a.totalPower);
  // Each input triangle once, in input order, through its canonical slot, with the same area and
  // CDF as without spatial splits (the table does not depend on the tree).
  std::vector<int> seen(tris.size(), 0);
  for (std::size_t k = 0; k < b.emitters.size(); ++k) {
    const Emitter& e = b.emitters[k];
    REQUIRE(e.tri < split.triangles.size());
    CHECK(as_uint(split.triangles[e.tri].e1.w) == e.tri);
    CHECK(split.order[e.tri] == plain.order[a.emitters[k].tri]);
    CHECK(e.area == a.emitters[k].area);
    CHECK(e.cdf == a.emitters[k].cdf);
    ++seen[split.order[e.tri]];
  }
  for (std::size_t i = 0; i < tris.size(); ++i) CHECK(seen[i] == (i % 3 != 0 ? 1 : 0));
}

TEST_CASE("bvh spatial: a direct-lighting render is bit-identical with and without spatial splits" * doctest::test_suite("cpu")) {
  // The sliver scene, every third triangle a lamp, seen from outside (no coincident triangles,
  // so no ties a different tree could resolve differently).
  Scene scene;
  scene.path = "<sliver scene>";
  scene.triangles = slivers(3000, 21u, 2.0f, 3);
  scene.materials = {MaterialDesc("grey", vec3(0.6f)), MaterialDesc("lamp", vec3(0.5f), vec3(4.0f)),
                     MaterialDesc("red", vec3(0.8f, 0.2f, 0.1f))};
  for (MaterialDesc& m : scene.materials) m.twoSidedEmission = true;
  scene.camera.position = vec3(3.0f, 4.0f, 14.0f);
  scene.camera.target = vec3(0.0f);
  scene.camera.width = 48;
  scene.camera.height = 32;
  scene.render.spp = 4;
  scene.render.integrator = Integrator::Direct;
  finishScene(scene);
  Bvh plain = buildBvh(scene.triangles, withSplits(0.0f)), split = buildBvh(scene.triangles, withSplits(0.3f));
  REQUIRE(split.triangles.size() > plain.triangles.size());
  const DeviceInfo host = selectDevice("host");
  RenderStats sa, sb;
  Film a = WavefrontRenderer(host, {}).render(scene, plain, sa);
  Film b = WavefrontRenderer(host, {}).render(scene, split, sb);
  double sum = 0.0;
  for (const glm::vec4& p : a.mean) sum += p.x + p.y + p.z;
  CHECK(sum > 0.0);  // not vacuous: lit
  CHECK(a.mean == b.mean);
  CHECK(a.m2 == b.m2);
  CHECK(a.count == b.count);
}

}  // namespace test_file_bvh_spatial
