// test_triangle_normals.cpp: the shade stages' precomputed per-triangle geometric normals and areas
// (render/triangle_shading.h buildTriangleNormals): against a double-precision computation, at
// any scale (a triangle scaled by a power of two keeps its normal's bits; its area scales exactly),
// and the 1-entry buffer of an empty list.
#include <doctest/doctest.h>

#include <cmath>

#include "bvh/bvh.h"
#include "render/triangle_shading.h"
#include "soups.h"

namespace test_file_triangle_normals {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using montecl_test::seededSoup;

namespace {

struct Ref {
  double n[3];
  double area;
};

Ref reference(const Triangle& t) {
  const double a[3] = {t.e1.x, t.e1.y, t.e1.z}, b[3] = {t.e2.x, t.e2.y, t.e2.z};
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  return Ref{{c[0] / len, c[1] / len, c[2] / len}, 0.5 * len};
}

Triangle scaled(const Triangle& t, float s) {
  Triangle r = t;
  r.v0 = float4(glm::vec3(t.v0) * s, t.v0.w);
  r.e1 = float4(glm::vec3(t.e1) * s, t.e1.w);
  r.e2 = float4(glm::vec3(t.e2) * s, t.e2.w);
  return r;
}

}  // namespace

TEST_CASE("triangle normals: unit geometric normal and area per BVH triangle, at any scale" * doctest::test_suite("cpu")) {
  const Bvh bvh = buildBvh(seededSoup(300, 11, 4.0f, 0.7f, 0.2f));
  const std::vector<float4> n = buildTriangleNormals(bvh.triangles);
  REQUIRE(n.size() == bvh.triangles.size());
  for (std::size_t i = 0; i < n.size(); ++i) {
    CAPTURE(i);
    const Ref r = reference(bvh.triangles[i]);
    for (int k = 0; k < 3; ++k) CHECK(std::fabs(double(n[i][k]) - r.n[k]) < 2e-6);
    CHECK(std::fabs(double(n[i].w) / r.area - 1.0) < 2e-6);
  }

  // 2^-40 and 2^40 times the same triangles: the normal's bits stay, the area by s^2 exactly
  // (edges of ~1e-12: a plain cross product's squared length, ~1e-48, would underflow).
  for (float s : {std::ldexp(1.0f, -40), std::ldexp(1.0f, 40)}) {
    std::vector<Triangle> tris;
    for (const Triangle& t : bvh.triangles) tris.push_back(scaled(t, s));
    const std::vector<float4> m = buildTriangleNormals(tris);
    for (std::size_t i = 0; i < m.size(); ++i) {
      CAPTURE(i);
      CHECK(glm::vec3(m[i]) == glm::vec3(n[i]));
      CHECK(m[i].w == n[i].w * s * s);
    }
  }
  CHECK(buildTriangleNormals({}).size() == 1);
}

}  // namespace test_file_triangle_normals
