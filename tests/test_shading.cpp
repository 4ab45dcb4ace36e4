// test_shading.cpp: per-triangle surface attributes (issue 11 §1): the device attribute buffer in
// BVH order (render/triangle_shading.h).
#include <doctest/doctest.h>

#include "bvh/bvh.h"
#include "render/triangle_shading.h"
#include "soups.h"

using namespace montecl;
using namespace montecl_test;

TEST_CASE("shading buffer: BVH order, flags in e2.w, a 1-entry dummy without attributes" * doctest::test_suite("cpu")) {
  std::vector<SceneTriangle> tris = seededSoup(200, 7, 2.0f, 0.5f, 0.1f);
  Bvh plain = buildBvh(tris);
  CHECK(buildTriangleShading(tris, plain).size() == 1);
  for (const Triangle& t : plain.triangles) CHECK(as_uint(t.e2.w) == 0u);

  // Every third triangle gets normals (some unnormalised), every fifth UVs; values name the input.
  for (std::size_t i = 0; i < tris.size(); ++i) {
    SceneTriangle& t = tris[i];
    if (i % 3 == 0) {
      t.attributes |= kHasNormals;
      for (int k = 0; k < 3; ++k) t.n[k] = glm::vec3(0.0f, 0.0f, 2.0f + float(k));
      t.n[1] = glm::vec3(3.0f, 4.0f, 0.0f);
    }
    if (i % 5 == 0) {
      t.attributes |= kHasUv;
      for (int k = 0; k < 3; ++k) t.uv[k] = glm::vec2(float(i), float(k) + 0.25f);
    }
  }
  Bvh bvh = buildBvh(tris);
  std::vector<TriangleShading> s = buildTriangleShading(tris, bvh);
  REQUIRE(s.size() == bvh.triangles.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    const std::uint32_t i = bvh.order[j];
    CAPTURE(i);
    CHECK(as_uint(bvh.triangles[j].e1.w) == i);
    CHECK(as_uint(bvh.triangles[j].e2.w) == tris[i].attributes);
    if (i % 3 == 0) {
      CHECK(glm::vec3(s[j].n0) == glm::vec3(0, 0, 1));
      CHECK(glm::vec3(s[j].n1) == glm::vec3(0.6f, 0.8f, 0.0f));
      CHECK(glm::vec3(s[j].n2) == glm::vec3(0, 0, 1));
    } else {
      CHECK(glm::vec3(s[j].n1) == glm::vec3(0.0f));
    }
    if (i % 5 == 0) {
      CHECK(s[j].n0.w == float(i));
      CHECK(s[j].n2.w == float(i));
      CHECK(s[j].tv == glm::vec4(0.25f, 1.25f, 2.25f, 0.0f));
    } else {
      CHECK(s[j].tv == glm::vec4(0.0f));
    }
  }
}
