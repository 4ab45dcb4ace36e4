// test_cli_camera_options.cpp: the camera from the command line, through the real command:
// --camera N picks a glTF file's perspective camera N (the first by default), --look-from and
// --look-at move and turn the chosen camera, --fov zooms it; out-of-range or malformed values are
// one line, exit 2. Reads what -v prints of the camera; writes its files in a temporary folder.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"
#include "mesh_files.h"

namespace test_file_cli_camera_options {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// The tent of mesh_files.h with two perspective cameras: camera 0 at (0, 1, 5) looking along -z,
// camera 1 at (6, 1, -1) looking along -x (turned 90 degrees about +y), 30 and 60 degrees tall.
std::string twoCameraGltf() {
  std::string text = gltfText(tentMesh(), 0.5f, "");
  const std::string scenes = R"("scenes":[{"nodes":[0]}])";
  const std::size_t in = text.find(scenes);
  REQUIRE(in != std::string::npos);
  text.replace(in, scenes.size(), R"("scenes":[{"nodes":[0,1,2]}])");
  const std::string nodes = R"("nodes":[{"mesh":0,"translation":[0,0,0]}])";
  const std::size_t at = text.find(nodes);
  REQUIRE(at != std::string::npos);
  const double yfov0 = 30.0 * 3.14159265358979 / 180.0, yfov1 = 60.0 * 3.14159265358979 / 180.0;
  return text.substr(0, at) +
         R"("nodes":[{"mesh":0,"translation":[0,0,0]},{"camera":0,"translation":[0,1,5]},)"
         R"({"camera":1,"translation":[6,1,-1],"rotation":[0,0.7071067811865476,0,0.7071067811865476]}],)"
         R"("cameras":[{"type":"perspective","perspective":{"yfov":)" + std::to_string(yfov0) +
         R"(,"znear":0.1}},{"type":"perspective","perspective":{"yfov":)" + std::to_string(yfov1) +
         R"(,"znear":0.1}}])" + text.substr(at + nodes.size());
}

std::vector<std::string> args(const TempDir& dir, const std::string& out) {
  return {"render", dir.file("cams.gltf"), "-o", dir.file(out), "--width", "8", "--height", "8", "--spp", "1",
          "--device", "host", "-q", "-v"};
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("cli: --camera N picks the file's camera N; --look-from, --look-at and --fov move it" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("cams.gltf", twoCameraGltf());
  // The default: camera 0; the loader says --camera picks another.
  const CliResult first = runMontecl(args(dir, "a.png"));
  INFO(first.err);
  REQUIRE(first.exitCode == 0);
  CHECK(has(cameraLine(first), "\"position\": [0, 1, 5]"));
  CHECK(has(cameraLine(first), "\"fov_y\": 30"));
  CHECK(has(first.err, "cams.gltf: 2 cameras; camera 0 is used (--camera N picks camera N, from 0; --camera all renders each)"));
  // --camera 1: the second camera, its own field of view; --width and --height still apply.
  std::vector<std::string> c1 = args(dir, "b.png");
  c1.insert(c1.end(), {"--camera", "1"});
  const CliResult second = runMontecl(c1);
  INFO(second.err);
  REQUIRE(second.exitCode == 0);
  CHECK(has(cameraLine(second), "\"position\": [6, 1, -1]"));
  CHECK(has(cameraLine(second), "\"fov_y\": 60"));
  CHECK(has(cameraLine(second), "\"width\": 8, \"height\": 8"));
  CHECK_FALSE(has(second.err, "cameras; camera 0 is used"));
  // --look-from / --look-at / --fov replace those of the camera chosen.
  std::vector<std::string> look = args(dir, "c.png");
  look.insert(look.end(), {"--camera", "1", "--look-from", "0,2,8", "--look-at", "1,0.5,-1", "--fov", "20"});
  const CliResult moved = runMontecl(look);
  INFO(moved.err);
  REQUIRE(moved.exitCode == 0);
  CHECK(has(cameraLine(moved), "\"position\": [0, 2, 8], \"target\": [1, 0.5, -1]"));
  CHECK(has(cameraLine(moved), "\"fov_y\": 20"));
}

TEST_CASE("cli: camera options out of range or malformed are one line, exit 2" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("cams.gltf", twoCameraGltf());
  const std::string out = dir.file("x.png");
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = args(dir, "x.png");
    a.insert(a.end(), extra.begin(), extra.end());
    return runMontecl(a);
  };
  checkRefused(with({"--camera", "2"}), out, {"--camera", "camera 2 out of range", "has 2 cameras"});
  checkRefused(with({"--look-from", "1,2"}), out, {"--look-from", "'1,2'", "X,Y,Z"});
  checkRefused(with({"--look-at", "0,x,0"}), out, {"--look-at", "'0,x,0'"});
  checkRefused(with({"--look-from", "0,1,5", "--look-at", "0,1,5"}), out, {"--look-from/--look-at", "unusable"});
  checkRefused(with({"--fov", "180"}), out, {"--fov"});
  checkRefused(with({"--camera", "1", "--view", "top"}), out, {"--camera", "--view"});
  // A model without cameras has none to pick.
  dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  std::vector<std::string> plain = {"render", dir.file("plain.obj"), "-o", out, "--camera", "0", "-q"};
  checkRefused(runMontecl(plain), out, {"--camera", "has 0 cameras"});
}

}  // namespace test_file_cli_camera_options
