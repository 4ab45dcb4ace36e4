// test_sort_by_kind.cpp: the fused path group's sort of bounce hits by material kind
// (kernels/stages/sort_by_kind.h), called on host arrays at W = 1 (its body is the same C at every
// width): misses first, then each kind in table order, each in queue order, with each entry's ray,
// hit, path id and hit instance moved together; and, through the real command, path renders of a
// scene of three kinds byte-identical sorted (fused, W = 16 and 4) and unsorted (the host backend,
// --no-fuse).
#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"
#include "kernels/stages/stages.h"

namespace test_file_sort_by_kind {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

TEST_CASE("sort by kind: misses first, kinds in table order, stable, every field of an entry moved together" *
          doctest::test_suite("cpu")) {
  // Four materials: diffuse, dielectric, conductor, diffuse; one triangle each.
  const uint kinds[4] = {MCL_MATERIAL_diffuse, MCL_MATERIAL_dielectric, MCL_MATERIAL_conductor, MCL_MATERIAL_diffuse};
  std::vector<Material> materials(4);
  std::vector<Triangle> tris(4);
  for (uint m = 0; m < 4; ++m) {
    materials[m] = Material{};
    materials[m].alpha.w = as_float(kinds[m]);
    tris[m] = Triangle{};
    tris[m].v0.w = as_float(m);  // triangle_material
  }
  // A group of 13 entries after 3 others (first = 3): their hit triangles (MCL_NO_HIT: a miss).
  const uint first = 3, n = 13;
  const uint hitTri[n] = {2, 0, MCL_NO_HIT, 1, 3, 2, MCL_NO_HIT, 0, 1, 1, 3, 2, 0};
  std::vector<Ray> rays(first + n);
  std::vector<Hit> hits(first + n);
  std::vector<uint> ids(first + n), inst(first + n);
  for (uint i = 0; i < first + n; ++i) {
    rays[i].origin = float4(float(i), 0.0f, 0.0f, 0.0f);
    rays[i].dir = float4(0.0f, 0.0f, 1.0f, float(100 + i));
    hits[i].tri = i < first ? 0u : hitTri[i - first];
    hits[i].t = float(i);
    ids[i] = 1000u + i;
    inst[i] = 500u + i;
  }
  const std::vector<Ray> rays0 = rays;
  fused_sort_by_kind(rays.data(), hits.data(), ids.data(), inst.data(), 1, tris.data(), materials.data(), first, n);
  // The expected order: each key's entries in their queue order.
  auto keyOf = [&](uint tri) { return tri == MCL_NO_HIT ? 0u : 1u + kinds[tri]; };
  std::vector<uint> expected;  // original positions
  for (uint key = 0; key <= MCL_MATERIAL_KIND_COUNT; ++key)
    for (uint i = 0; i < n; ++i)
      if (keyOf(hitTri[i]) == key) expected.push_back(first + i);
  REQUIRE(expected.size() == n);
  for (uint i = 0; i < first; ++i) CHECK(ids[i] == 1000u + i);  // entries before the group stay
  for (uint j = 0; j < n; ++j) {
    const uint from = expected[j], at = first + j;
    CAPTURE(at);
    CHECK(ids[at] == 1000u + from);
    CHECK(inst[at] == 500u + from);
    CHECK(hits[at].t == float(from));
    CHECK(hits[at].tri == hitTri[from - first]);
    CHECK(rays[at].origin.x == rays0[from].origin.x);
    CHECK(rays[at].dir.w == rays0[from].dir.w);
  }
  // One kind only: nothing moves.
  std::vector<uint> same = ids;
  for (uint i = first; i < first + n; ++i) hits[i].tri = 1u;
  fused_sort_by_kind(rays.data(), hits.data(), ids.data(), inst.data(), 0, tris.data(), materials.data(), first, n);
  CHECK(ids == same);
}

TEST_CASE("sort by kind: path renders of glass, metals and a diffuse box are byte-identical sorted and unsorted" *
          doctest::test_suite("cli")) {
  TempDir dir;
  const std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/materials/scene.json";
  const std::vector<std::string> common = {"render", scene, "-q", "--width", "20", "--height", "16", "--integrator", "path",
                                     "--spp", "16", "--max-depth", "6", "--overwrite"};
  checkLanesMatchHostCli(common, dir, ".pfm");
}

}  // namespace test_file_sort_by_kind
