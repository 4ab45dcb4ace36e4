// test_cli_gltf_scenes.cpp: --scene N through the real command: a glTF file's scenes[] entry N is
// loaded (default: the file's "scene", else 0, with a warning naming --scene when there are
// several); an index the file does not have, or --scene with a model that is not glTF, is one
// line, exit 2. Reads what -v prints of the camera; writes its files in a temporary folder.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"
#include "mesh_files.h"

namespace test_file_cli_gltf_scenes {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// The tent of mesh_files.h in two scenes: scene 0 holds node 0 (the tent at the origin, no
// camera), scene 1 node 1 (the tent moved to x = 10) and node 2 (a camera at (10, 1, 6)).
// defaultScene: the file's "scene" key, or none when negative.
std::string twoSceneGltf(int defaultScene) {
  std::string text = gltfText(tentMesh(), 0.5f, "");
  const std::string head = R"("scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,0,0]}])";
  const std::size_t at = text.find(head);
  REQUIRE(at != std::string::npos);
  const std::string scene = defaultScene < 0 ? "" : "\"scene\":" + std::to_string(defaultScene) + ",";
  return text.substr(0, at) + scene +
         R"("scenes":[{"nodes":[0]},{"nodes":[1,2]}],)"
         R"("nodes":[{"mesh":0,"translation":[0,0,0]},{"mesh":0,"translation":[10,0,0]},)"
         R"({"camera":0,"translation":[10,1,6]}],)"
         R"("cameras":[{"type":"perspective","perspective":{"yfov":0.6,"znear":0.1}}])" + text.substr(at + head.size());
}

// The render of file to out.png (refused: to no.png, which the checks look for), 8x8, 1 spp, -v.
std::vector<std::string> args(const TempDir& dir, const std::string& file, std::vector<std::string> extra = {}) {
  std::vector<std::string> a = {"render", dir.file(file), "-o", dir.file("out.png"), "--width", "8", "--height", "8",
                                "--spp", "1", "--device", "host", "-q", "-v"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

std::vector<std::string> refused(const TempDir& dir, const std::string& file, std::vector<std::string> extra) {
  std::vector<std::string> a = args(dir, file, extra);
  a[3] = dir.file("no.png");
  return a;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("cli: --scene N loads a glTF file's scene N; the default is the file's scene, else 0" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("none.gltf", twoSceneGltf(-1));
  dir.write("one.gltf", twoSceneGltf(1));
  // No "scene" key: scene 0, framed automatically (no camera in it); the warning names --scene.
  const CliResult plain = runMontecl(args(dir, "none.gltf"));
  INFO(plain.err);
  REQUIRE(plain.exitCode == 0);
  CHECK(has(plain.err, "none.gltf: 2 scenes; scene 0 (the file's default) is used (--scene N picks scene N, from 0)"));
  CHECK_FALSE(has(cameraLine(plain), "\"position\": [10, 1, 6]"));
  // "scene": 1 is the default: scene 1's camera is used.
  const CliResult fileDefault = runMontecl(args(dir, "one.gltf"));
  INFO(fileDefault.err);
  REQUIRE(fileDefault.exitCode == 0);
  CHECK(has(fileDefault.err, "one.gltf: 2 scenes; scene 1 (the file's default) is used"));
  CHECK(has(cameraLine(fileDefault), "\"position\": [10, 1, 6]"));
  // --scene 1 and --scene 0 override it; no warning once the scene is chosen.
  const CliResult one = runMontecl(args(dir, "none.gltf", {"--scene", "1"}));
  INFO(one.err);
  REQUIRE(one.exitCode == 0);
  CHECK(has(cameraLine(one), "\"position\": [10, 1, 6]"));
  CHECK_FALSE(has(one.err, "2 scenes"));
  const CliResult zero = runMontecl(args(dir, "one.gltf", {"--scene", "0"}));
  INFO(zero.err);
  REQUIRE(zero.exitCode == 0);
  CHECK_FALSE(has(cameraLine(zero), "\"position\": [10, 1, 6]"));
  // The same camera as scene 1's through --camera 0 when its scene is loaded, none in scene 0.
  checkRefused(runMontecl(refused(dir, "one.gltf", {"--scene", "0", "--camera", "0"})), dir.file("no.png"),
               {"--camera", "has 0 cameras"});
}

TEST_CASE("cli: --scene out of range, or with a model that is not glTF, is one line, exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("two.gltf", twoSceneGltf(0));
  const std::string out = dir.file("no.png");
  checkRefused(runMontecl(refused(dir, "two.gltf", {"--scene", "2"})), out,
               {"--scene", "scene 2 out of range", "two.gltf has 2 scenes (from 0)"});
  checkRefused(runMontecl(refused(dir, "two.gltf", {"--scene", "-1"})), out, {"--scene"});
  // A file without scenes[] renders every root node; no index is in range.
  std::string bare = twoSceneGltf(-1);
  const std::string scenes = R"("scenes":[{"nodes":[0]},{"nodes":[1,2]}],)";
  bare.erase(bare.find(scenes), scenes.size());
  dir.write("bare.gltf", bare);
  REQUIRE(runMontecl(args(dir, "bare.gltf")).exitCode == 0);
  checkRefused(runMontecl(refused(dir, "bare.gltf", {"--scene", "0"})), out, {"--scene", "bare.gltf has no scenes[]"});
  dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  checkRefused(runMontecl(refused(dir, "plain.obj", {"--scene", "0"})), out, {"--scene", "plain.obj is not a glTF file"});
  dir.write("scene.json", R"({"camera":"auto","meshes":[{"file":"two.gltf"}]})");
  checkRefused(runMontecl(refused(dir, "scene.json", {"--scene", "1"})), out, {"--scene", "scene.json is not a glTF file"});
}

}  // namespace test_file_cli_gltf_scenes
