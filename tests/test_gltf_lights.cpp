// test_gltf_lights.cpp: glTF KHR_lights_punctual onto montecl's lights: point, spot and directional
// placed by their nodes (translation, rotation: a light shines down its node's -z), colour x
// intensity 1:1, spot cones in degrees; a scene file's mesh transform moves them too; bad lights
// are one InputError line; and through the command line a bare glTF lit only by its light renders
// lit (no "nothing emits" warning).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_gltf_lights {  // keeps this file's helpers apart in a unity batch

using montecl::LightDesc;
using montecl::PunctualKind;
using montecl::Scene;
using montecl_test::TempDir;
using nlohmann::json;

namespace {

// The tent with three lit nodes: a point at (1, 3, 0); a spot at (0, 2, 0) rotated so its -z points
// down (-y); a directional light turned the same way.
json litTent() {
  json g = json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, ""));
  const double s = std::sqrt(0.5);  // quaternion (x, y, z, w) of -90 degrees about +x: -z -> -y
  g["nodes"].push_back({{"translation", {1, 3, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  g["nodes"].push_back({{"translation", {0, 2, 0}}, {"rotation", {-s, 0, 0, s}},
                        {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  g["nodes"].push_back({{"rotation", {-s, 0, 0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  g["scenes"][0]["nodes"] = {0, 1, 2, 3};
  g["extensionsUsed"] = {"KHR_lights_punctual"};
  g["extensions"] = {{"KHR_lights_punctual",
                      {{"lights",
                        {{{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 4}},
                         {{"type", "spot"}, {"intensity", 2}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
                         {{"type", "directional"}, {"color", {0.5, 0.5, 0.5}}, {"intensity", 3}, {"range", 10}}}}}}};
  return g;
}

bool near(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) < 1e-5f; }

std::string loadError(const std::string& path) {
  try {
    Scene s;
    std::vector<std::string> w;
    montecl::loadGltfInto(path, s, &w, nullptr);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("glTF: KHR_lights_punctual point, spot and directional lights are placed by their nodes" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("lit.gltf", litTent().dump());
  Scene s;
  std::vector<std::string> warnings;
  montecl::loadGltfInto(dir.file("lit.gltf"), s, &warnings, nullptr);
  REQUIRE(s.lights.size() == 3);
  const LightDesc &point = s.lights[0], &spot = s.lights[1], &sun = s.lights[2];
  CHECK(point.kind == PunctualKind::Point);
  CHECK(near(point.position, {1, 3, 0}));
  CHECK(near(point.color, {4, 2, 1}));
  CHECK(spot.kind == PunctualKind::Spot);
  CHECK(near(spot.position, {0, 2, 0}));
  CHECK(near(spot.direction, {0, -1, 0}));
  CHECK(near(spot.color, {2, 2, 2}));
  CHECK(spot.beamDegrees == doctest::Approx(0.25 * 180 / M_PI));
  CHECK(spot.cutoffDegrees == doctest::Approx(0.5 * 180 / M_PI));
  CHECK(sun.kind == PunctualKind::Directional);
  CHECK(near(sun.direction, {0, -1, 0}));
  CHECK(near(sun.color, {1.5f, 1.5f, 1.5f}));
  std::string all;
  for (const std::string& w : warnings) all += w + "\n";
  INFO(all);
  CHECK(all.find("KHR_lights_punctual' not used") == std::string::npos);
  CHECK(all.find("lights[2].range: range not used by montecl") != std::string::npos);

  // Through a scene file, the mesh entry's transform moves the lights with the triangles.
  dir.write("scene.json", R"({"camera": {"position": [0, 1, 6], "target": [0, 0, 0], "fov_y": 40, "width": 8, "height": 8},
    "lights": [{"type": "point", "position": [0, 5, 0], "intensity": [1, 1, 1]}],
    "meshes": [{"file": "lit.gltf", "transform": {"translate": [10, 0, 0]}}]})");
  std::vector<std::string> w2;
  const Scene moved = montecl::loadScene(dir.file("scene.json"), w2);
  REQUIRE(moved.lights.size() == 4);  // the scene file's own, then the glTF's
  CHECK(near(moved.lights[0].position, {0, 5, 0}));
  CHECK(near(moved.lights[1].position, {11, 3, 0}));
  CHECK(near(moved.lights[2].direction, {0, -1, 0}));

  // Bad lights: one line naming the light and the key.
  json bad = litTent();
  bad["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1;
  dir.write("bad.gltf", bad.dump());
  CHECK(loadError(dir.file("bad.gltf")).find("KHR_lights_punctual.lights[0].intensity: must be finite and >= 0") != std::string::npos);
  bad = litTent();
  bad["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.6;
  dir.write("bad.gltf", bad.dump());
  CHECK(loadError(dir.file("bad.gltf")).find("lights[1].spot.innerConeAngle: must be in [0, outerConeAngle)") != std::string::npos);
  bad = litTent();
  bad["extensions"]["KHR_lights_punctual"]["lights"][2]["type"] = "area";
  dir.write("bad.gltf", bad.dump());
  CHECK(loadError(dir.file("bad.gltf")).find("lights[2].type: unknown light type 'area'") != std::string::npos);
  bad = litTent();
  bad["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 7;
  dir.write("bad.gltf", bad.dump());
  CHECK(loadError(dir.file("bad.gltf")).find("light index 7 out of range") != std::string::npos);
}

TEST_CASE("glTF: a bare glTF lit only by its KHR_lights_punctual light renders lit through the command line" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("lit.gltf", litTent().dump());
  const montecl_test::CliResult r =
      montecl_test::runMontecl({"render", dir.file("lit.gltf"), "-o", dir.file("out.pfm"), "--width", "16", "--height",
                                "16", "--spp", "2", "--integrator", "direct"});
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("nothing emits") == std::string::npos);
}

}  // namespace test_file_gltf_lights
