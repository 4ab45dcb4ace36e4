// test_bench.cpp: `montecl bench` and `montecl generate` through the real command line: a tiny
// generated terrain scene and the demo scene at a small resolution, JSON parsed and checked (zero
// mismatches per ray kind, the ray counts the spec gives, positive throughput, visit counts), the
// visit counter's exact counts on one triangle, plus the exact
// triangle count of the generator and bench's exit codes.
#include <doctest/doctest.h>


#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "bvh/bvh_visit_counts.h"
#include "cli_runner.h"

namespace test_file_bench {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  return nlohmann::json::parse(in);
}

std::size_t countFaces(const std::string& objPath) {
  std::ifstream in(objPath);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) n += line.rfind("f ", 0) == 0;
  return n;
}

const nlohmann::json* findKind(const nlohmann::json& r, const std::string& kind) {
  for (const auto& k : r["rays"])
    if (k["kind"] == kind) return &k;
  return nullptr;
}

// The checks every bench run must pass; primaryHits returns the primary hit count.
void checkBenchJson(const nlohmann::json& r, int width, int height, bool expectShadow) {
  REQUIRE(r.contains("rays"));
  CHECK(r["bvh"]["build_ms"].get<double>() >= 0.0);
  CHECK(r["bvh"]["nodes"].get<std::size_t>() >= 1);
  CHECK(r["bvh"]["sah_cost"].get<double>() > 0.0);
  const nlohmann::json* primary = findKind(r, "primary");
  const nlohmann::json* ao = findKind(r, "ao");
  REQUIRE(primary != nullptr);
  REQUIRE(ao != nullptr);
  CHECK((*primary)["count"].get<std::size_t>() == std::size_t(width) * std::size_t(height));
  std::size_t hits = (*primary)["hits"].get<std::size_t>();
  CHECK(hits > 0);
  CHECK((*ao)["count"].get<std::size_t>() == 8 * hits);
  const nlohmann::json* bounce = findKind(r, "bounce");  // the "diffuse bounce" set: closest hit
  REQUIRE(bounce != nullptr);
  CHECK((*bounce)["count"].get<std::size_t>() == 4 * hits);
  CHECK((*bounce)["query"] == "closest");
  CHECK((findKind(r, "shadow") != nullptr) == expectShadow);
  for (const auto& k : r["rays"]) {
    INFO("ray kind " << k["kind"]);
    CHECK(k["mismatches"].get<std::size_t>() == 0);
    CHECK(k["mrays_per_s"].get<double>() > 0.0);
    CHECK(k["min_ms"].get<double>() <= k["median_ms"].get<double>());
    if (r.contains("embree")) {
      CHECK(k["embree_mrays_per_s"].get<double>() > 0.0);
      CHECK(k["ratio"].get<double>() > 0.0);
    }
    // Visit counts with the wide layout: at least the root per ray, a leaf per closest hit.
    CHECK(k.contains("visits_nodes") == (r["bvh"]["layout"] == "wide"));
    if (k.contains("visits_nodes")) {
      CHECK(k["visits_nodes"].get<double>() >= 1.0);
      if (k["query"] == "closest")
        CHECK(k["visits_leaves"].get<double>() >= double(k["hits"].get<std::size_t>()) / double(k["count"].get<std::size_t>()));
    }
  }
  CHECK(r["mismatches_total"].get<std::size_t>() == 0);
}

}  // namespace

TEST_CASE("generate terrain writes exactly the requested triangle count" * doctest::test_suite("cli")) {
  TempDir dir;
  for (int n : {1, 2, 7, 1000, 1001, 4096}) {
    INFO("triangles " << n);
    std::string obj = dir.file("t" + std::to_string(n) + ".obj");
    CliResult r = runMontecl({"generate", "terrain", "--triangles", std::to_string(n), "-o", obj});
    REQUIRE(r.exitCode == 0);
    CHECK(countFaces(obj) == std::size_t(n));
  }
}

TEST_CASE("bench on a generated 1k-triangle terrain: all rays match, counts as specified" * doctest::test_suite("cli")) {
  TempDir dir;
  CliResult g = runMontecl({"generate", "terrain", "--triangles", "1000", "-o", dir.file("terrain.obj"), "--scene",
                            dir.file("terrain.json"), "--width", "32", "--height", "24"});
  REQUIRE(g.exitCode == 0);
  CliResult r = runMontecl({"bench", dir.file("terrain.json"), "--repeat", "2", "--json", dir.file("out.json"), "-q"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("Mrays/s") != std::string::npos);
  nlohmann::json j = readJson(dir.file("out.json"));
  CHECK(j["triangles"].get<std::size_t>() == 1002);  // terrain + the emissive quad
  CHECK(j["emitters"].get<std::size_t>() == 2);
  checkBenchJson(j, 32, 24, /*expectShadow=*/true);
}

TEST_CASE("bench on the demo scene at a small resolution" * doctest::test_suite("cli")) {
  TempDir dir;
  CliResult r = runMontecl({"bench", MONTECL_SOURCE_DIR "/scenes/demo/scene.json", "--width", "40", "--height", "30",
                            "--repeat", "1", "--threads", "2", "--json", dir.file("demo.json"), "-q"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  checkBenchJson(readJson(dir.file("demo.json")), 40, 30, /*expectShadow=*/true);  // demo has a lamp
}

TEST_CASE("bench with the binary BVH layout: all rays match its host reference" * doctest::test_suite("cli")) {
  TempDir dir;
  CliResult r = runMontecl({"bench", MONTECL_SOURCE_DIR "/scenes/demo/scene.json", "--width", "40", "--height", "30",
                            "--repeat", "1", "--bvh-layout", "binary", "--no-embree", "--json", dir.file("b.json"),
                            "-q"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  nlohmann::json j = readJson(dir.file("b.json"));
  CHECK(j["bvh"]["layout"] == "binary");
  CHECK(j["mismatches_total"].get<std::size_t>() == 0);
  CHECK(runMontecl({"bench", MONTECL_SOURCE_DIR "/scenes/demo/scene.json", "--bvh-layout", "quad"}).exitCode == 2);
}

TEST_CASE("bench bad input exits 2 with one line" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  CliResult r = runMontecl({"bench", dir.file("missing.json")});
  CHECK(r.exitCode == 2);
  CHECK(r.err.find('\n') == r.err.size() - 1);
  CliResult j = runMontecl({"bench", MONTECL_SOURCE_DIR "/scenes/demo/scene.json", "--json",
                            dir.file("no/such/folder/out.json")});
  CHECK(j.exitCode == 2);
}

TEST_CASE("bench visit counts: one triangle is the root node and one leaf" * doctest::test_suite("cpu")) {
  using namespace montecl;
  SceneTriangle t;
  t.v[0] = glm::vec3(0, 0, 0);
  t.v[1] = glm::vec3(1, 0, 0);
  t.v[2] = glm::vec3(0, 1, 0);
  t.material = 0;
  Bvh bvh = buildBvh({t});
  auto ray = [](glm::vec3 o, glm::vec3 d, float tmax) {
    Ray r;
    r.origin = glm::vec4(o, 0.0f);
    r.dir = glm::vec4(d, tmax);
    return r;
  };
  const Ray hit = ray({0.25f, 0.25f, 1.0f}, {0, 0, -1}, INFINITY);
  const Ray inBoxMiss = ray({0.9f, 0.9f, 1.0f}, {0, 0, -1}, INFINITY);  // enters the box, misses
  const Ray outside = ray({5.0f, 5.0f, 1.0f}, {0, 0, -1}, INFINITY);
  const Ray nonFinite = ray({NAN, 0.0f, 1.0f}, {0, 0, -1}, INFINITY);
  for (bool any : {false, true}) {
    CAPTURE(any);
    VisitCounts c = countWideVisits(bvh, {hit}, any);
    CHECK(c.nodes == 1.0);
    CHECK(c.leaves == 1.0);
    c = countWideVisits(bvh, {inBoxMiss}, any);
    CHECK(c.nodes == 1.0);
    CHECK(c.leaves == 1.0);
    c = countWideVisits(bvh, {outside}, any);
    CHECK(c.nodes == 1.0);
    CHECK(c.leaves == 0.0);
    c = countWideVisits(bvh, {nonFinite}, any);
    CHECK(c.nodes == 0.0);
    c = countWideVisits(bvh, {hit, outside, hit, nonFinite}, any, nullptr, 3);  // means, any threads
    CHECK(c.nodes == 0.75);
    CHECK(c.leaves == 0.5);
  }
}

}  // namespace test_file_bench
