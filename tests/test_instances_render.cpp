// test_instances_render.cpp: renders through the two-level BVH: a scene file's 125 instances of one
// mesh render like the same scene flattened into 125 copies (depth AOV, per-pixel z-test of the
// image, for AO, direct and path), emissive instances stay copies, bounds and digest count the
// placements, --bvh-layout binary is refused in one line, and the conformance set's instanced
// case (host backend vs OpenCL devices, bit for bit) has its instances in view.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bvh/bvh_instances.h"
#include "cl/devices.h"
#include "conformance/scenes.h"
#include "cli_runner.h"
#include "mesh_files.h"
#include "render/wavefront.h"
#include "scene/scene.h"
#include "scene/scene_digest.h"
#include "scene/scene_instances.h"

namespace test_file_instances_render {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
using nlohmann::json;

namespace {

// 125 placements of the tent on a 5 x 5 x 5 grid: turned about y, mostly scaled by 0.6, some
// non-uniformly, some mirrored in x.
json tentPlacements() {
  json list = json::array();
  for (int i = 0; i < 125; ++i) {
    const int ix = i % 5, iy = (i / 5) % 5, iz = i / 25;
    json scale = {0.6, 0.6, 0.6};
    if (i % 5 == 1) scale = {0.8, 0.4, 0.6};
    if (i % 7 == 0) scale = {-0.6, 0.6, 0.6};
    list.push_back({{"translate", {-4.0 + 2.0 * ix, 0.7 * iy, -4.0 + 2.0 * iz}}, {"rotate", {0, 1, 0, 17.0 * i + 3.0}},
                    {"scale", scale}});
  }
  return list;
}

// A floor, a two-sided emitting quad above it (as two instances: emitting, so flattened) and the
// tent's 125 instances (glossy, with corner normals and UVs).
json instancedScene(const std::string& integrator) {
  return {{"camera", {{"position", {0, 7, 10}}, {"target", {0, 0.5, 0}}, {"fov_y", 50}, {"width", 64}, {"height", 48}}},
          {"render", {{"integrator", integrator}, {"spp", 4}, {"sampler", "independent"}, {"seed", 3}}},
          {"meshes",
           {{{"file", "floor.obj"}, {"material", {{"albedo", {0.5, 0.5, 0.5}}}}},
            {{"file", "light.obj"},
             {"emission", {4, 4, 4}},
             {"two_sided_emission", true},
             {"instances", {{{"translate", {-1.5, 0, 0}}}, {{"translate", {1.5, 0, 0}}}}}},
            {{"file", "tent.obj"},
             {"material", {{"albedo", {0.6, 0.3, 0.2}}, {"specular", {0.3, 0.3, 0.3}}, {"specular_exponent", 40}}},
             {"instances", tentPlacements()}}}}};
}

void writeMeshes(TempDir& dir) {
  dir.write("tent.obj", montecl_test::objText(montecl_test::tentMesh()));
  dir.write("floor.obj", "v -6 0 -6\nv 6 0 -6\nv 6 0 6\nv -6 0 6\nf 1 4 3 2\n");
  dir.write("light.obj", "v -1 5 -1\nv 1 5 -1\nv 1 5 1\nv -1 5 1\nf 1 2 3 4\n");
}

Film renderWithAovs(const Scene& s) {
  static const DeviceInfo device = selectDevice("host");
  const Bvh bvh = buildSceneBvh(s);
  RenderOptions o;
  o.aovs = true;
  WavefrontRenderer r(device, o);
  RenderStats stats;
  return r.render(s, bvh, stats);
}

}  // namespace

TEST_CASE("instances: 125 instances render like 125 flattened copies (depth within 1e-5, image z-test)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeMeshes(dir);
  for (const std::string integrator : {"ao", "direct", "path"}) {
    CAPTURE(integrator);
    dir.write("scene.json", instancedScene(integrator).dump());
    std::vector<std::string> warnings;
    const Scene inst = loadScene(dir.file("scene.json"), warnings);
    REQUIRE(inst.instances.size() == 125);
    REQUIRE(inst.meshRanges.size() == 1);
    Scene flat = inst;
    flattenInstances(flat);
    REQUIRE(flat.triangles.size() == 2 + 4 + 125 * 4);
    REQUIRE(buildSceneBvh(inst).instances.size() == 126);  // the world triangles' identity and the tents
    const Film a = renderWithAovs(inst), b = renderWithAovs(flat);
    REQUIRE(a.mean.size() == b.mean.size());
    std::size_t hits = 0, depthOff = 0, zOff = 0;
    double worstZ = 0.0;
    for (std::size_t p = 0; p < a.mean.size(); ++p) {
      const double na = double(a.count[p]), nb = double(b.count[p]);
      const double da = a.aovSum[MCL_AOV_VECTORS * p].w / na, db = b.aovSum[MCL_AOV_VECTORS * p].w / nb;
      hits += da > 0.0;
      depthOff += !(std::fabs(da - db) <= 1e-5 * std::max(da, db));
      for (int c = 0; c < 3; ++c) {
        const double ma = a.meanOf(p, c), mb = b.meanOf(p, c);
        const double se = std::sqrt(a.meanVariance(p, c) + b.meanVariance(p, c));
        const double slack = 1e-4 * std::max(std::fabs(ma), std::fabs(mb)) + 1e-6;  // rounding where var is 0
        if (!(std::fabs(ma - mb) <= 5.0 * se + slack)) ++zOff;
        if (se > 0.0) worstZ = std::max(worstZ, std::fabs(ma - mb) / se);
      }
    }
    INFO("pixels hit " << hits << ", depth off " << depthOff << ", z off " << zOff << ", worst z " << worstZ);
    CHECK(hits > a.mean.size() / 2);
    CHECK(depthOff == 0);
    CHECK(zOff == 0);
  }
}

TEST_CASE("instances: a scene file keeps non-emitting instances as one mesh; bounds and digest count the placements" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  writeMeshes(dir);
  json j = instancedScene("direct");
  dir.write("scene.json", j.dump());
  std::vector<std::string> warnings;
  const Scene s = loadScene(dir.file("scene.json"), warnings);
  CHECK(s.triangles.size() == 2 + 2 * 2 + 4);  // the emitting quad's two copies, the tent once
  CHECK(placedTriangleCount(s) == 2 + 4 + 125 * 4);
  Scene flat = s;
  flattenInstances(flat);
  for (const SceneTriangle& t : flat.triangles)
    for (const glm::vec3& v : t.v) {
      CHECK(glm::all(glm::greaterThanEqual(v, s.boundsMin)));
      CHECK(glm::all(glm::lessThanEqual(v, s.boundsMax)));
    }
  // The top grid layer reaches y = 2.8 + the tent's height: the bounds are the placed ones.
  CHECK(s.boundsMax.y > 2.8f + 0.6f * 1.5f * 0.99f);
  // One placement moved: another scene, another digest.
  j["meshes"][2]["instances"][7]["translate"] = {0.5, 0, 0};
  dir.write("moved.json", j.dump());
  const Scene moved = loadScene(dir.file("moved.json"), warnings);
  CHECK(moved.triangles.size() == s.triangles.size());
  CHECK(sceneDigest(moved) != sceneDigest(s));
}

TEST_CASE("instances: --bvh-layout binary with instances is one line naming the option, exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeMeshes(dir);
  dir.write("scene.json", instancedScene("ao").dump());
  const CliResult r = runMontecl({"render", dir.file("scene.json"), "-o", dir.file("out.pfm"), "-q", "--device", "host",
                                  "--bvh-layout", "binary"});
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(dir.file("scene.json") + ": --bvh-layout: binary cannot render the scene's instances") !=
        std::string::npos);
  // wide (and auto) render it.
  const CliResult w = runMontecl({"render", dir.file("scene.json"), "-o", dir.file("out.pfm"), "-q", "--device", "host",
                                  "--bvh-layout", "wide", "--spp", "1"});
  CHECK_MESSAGE(w.exitCode == 0, w.err);
}

TEST_CASE("instances: the conformance set's instanced spheres cover part of its images" * doctest::test_suite("cpu")) {
  std::vector<std::string> skipped;
  ConformanceSetOptions o;
  o.cornellPath = "/nonexistent";
  int found = 0;
  for (const ConformanceCase& c : conformanceSet(o, skipped)) {
    if (c.name.rfind("instanced-spheres/", 0) != 0) continue;
    CAPTURE(c.name);
    ++found;
    REQUIRE(c.scene.meshRanges.size() == 1);
    CHECK(c.scene.instances.size() == 6);
    Scene without = c.scene;  // the spheres' range is the last run of triangles
    without.triangles.resize(without.meshRanges[0].firstTri);
    without.meshRanges.clear();
    without.instances.clear();
    const Film a = renderWithAovs(c.scene), b = renderWithAovs(without);
    std::size_t covered = 0;
    for (std::size_t p = 0; p < a.mean.size(); ++p)
      covered += a.aovSum[MCL_AOV_VECTORS * p].w != b.aovSum[MCL_AOV_VECTORS * p].w;
    INFO("pixels covered " << covered << " of " << a.mean.size());
    CHECK(covered >= a.mean.size() / 10);
  }
  CHECK(found == 4);  // ao-cosine, direct-mis, path, path-blend
}

}  // namespace test_file_instances_render
