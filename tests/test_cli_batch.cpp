// test_cli_batch.cpp: several views in one `montecl render`, through the real command: --camera all
// and --camera N,M,... write one image per camera, named by the output pattern's {camera}, each the
// same bytes as that camera rendered alone; without -o each is <model>_<camera>.png; a pattern that
// cannot name the views, and options that name one view, are one line, exit 2, before anything is
// written. Writes its files in a temporary folder.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"
#include "mesh_files.h"

namespace test_file_cli_batch {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// The tent of mesh_files.h seen by three perspective cameras: camera 0 from +z, camera 1 from +x
// (turned 90 degrees about +y, 60 degrees tall), camera 2 from +z again, further away and 3:2.
std::string threeCameraGltf() {
  std::string text = gltfText(tentMesh(), 0.5f, "");
  const std::string head = R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,0,0]}])";
  const std::size_t at = text.find(head);
  REQUIRE(at != std::string::npos);
  return text.substr(0, at) +
         R"("scenes":[{"nodes":[0,1,2,3]}],"nodes":[{"mesh":0,"translation":[0,0,0]},)"
         R"({"camera":0,"translation":[1,1,5]},)"
         R"({"camera":1,"translation":[7,1,-1],"rotation":[0,0.7071067811865476,0,0.7071067811865476]},)"
         R"({"camera":2,"translation":[1,1,9]}],)"
         R"("cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}},)"
         R"({"type":"perspective","perspective":{"yfov":1.0,"znear":0.1}},)"
         R"({"type":"perspective","perspective":{"yfov":0.5,"aspectRatio":1.5,"znear":0.1}}])" +
         text.substr(at + head.size());
}

std::vector<std::string> render(const TempDir& dir, std::vector<std::string> extra) {
  std::vector<std::string> a = {"render", dir.file("cams.gltf"), "--height", "8", "--spp", "2", "--device", "host", "-q"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("cli: --camera all writes one image per camera, each the bytes of that camera rendered alone" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("cams.gltf", threeCameraGltf());
  const CliResult all = runMontecl(render(dir, {"--camera", "all", "-o", dir.file("v_{camera}.png")}));
  INFO(all.err);
  REQUIRE(all.exitCode == 0);
  // One "wrote" line per view, in camera order; camera 2 keeps its 3:2 shape at --height 8.
  const std::size_t w0 = all.out.find("wrote " + dir.file("v_0.png") + ": 512x8,");
  const std::size_t w1 = all.out.find("wrote " + dir.file("v_1.png") + ": 512x8,");
  const std::size_t w2 = all.out.find("wrote " + dir.file("v_2.png") + ": 768x8,");
  CHECK(w0 != std::string::npos);
  CHECK(w1 != std::string::npos);
  CHECK(w2 != std::string::npos);
  CHECK((w0 < w1 && w1 < w2));
  CHECK(dir.entries() == std::vector<std::string>{"cams.gltf", "v_0.png", "v_1.png", "v_2.png"});
  // Each image is its camera's alone, and the three differ.
  for (const char* c : {"0", "1", "2"}) {
    const std::string single = dir.file(std::string("single_") + c + ".png");
    REQUIRE(runMontecl(render(dir, {"--camera", c, "-o", single})).exitCode == 0);
    CHECK(readAll(single) == readAll(dir.file(std::string("v_") + c + ".png")));
  }
  CHECK(readAll(dir.file("v_0.png")) != readAll(dir.file("v_1.png")));
  // A list renders the cameras named, in its order.
  const CliResult some = runMontecl(render(dir, {"--camera", "2,0", "-o", dir.file("s{camera}.png")}));
  INFO(some.err);
  REQUIRE(some.exitCode == 0);
  CHECK(some.out.find("s2.png") < some.out.find("s0.png"));
  CHECK(std::filesystem::exists(dir.file("s0.png")));
  CHECK_FALSE(std::filesystem::exists(dir.file("s1.png")));
  CHECK(readAll(dir.file("s2.png")) == readAll(dir.file("v_2.png")));
  // Every {camera} of the pattern is replaced, and one camera may be named by a pattern too.
  REQUIRE(runMontecl(render(dir, {"--camera", "1", "-o", dir.file("{camera}_v{camera}.png")})).exitCode == 0);
  CHECK(readAll(dir.file("1_v1.png")) == readAll(dir.file("v_1.png")));
  // Without -o: <model>_<camera>.png in the current folder, never replacing a file.
  dir.write("cams_1.png", "keep me");
  const CliResult named = runMonteclIn(dir.path, render(dir, {"--camera", "all"}));
  INFO(named.err);
  REQUIRE(named.exitCode == 0);
  CHECK(has(named.out, "wrote cams_0.png: "));
  CHECK(has(named.out, "wrote cams_1-1.png: "));
  CHECK(has(named.out, "wrote cams_2.png: "));
  CHECK(readAll(dir.file("cams_1.png")) == "keep me");
}

TEST_CASE("cli: a batch's bad pattern or single-view options are one line, exit 2, before any image" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("cams.gltf", threeCameraGltf());
  const std::string out = dir.file("out.png");
  const auto refused = [&](std::vector<std::string> extra, const std::vector<std::string>& words) {
    const CliResult r = runMontecl(render(dir, extra));
    checkRefused(r, out, words);
    CHECK(dir.entries() == std::vector<std::string>{"cams.gltf"});  // nothing written, not one view
  };
  refused({"--camera", "all", "-o", out}, {"-o", "has no {camera}", "--camera all", "out_{camera}.png"});
  refused({"--camera", "0,2", "-o", out}, {"-o", "has no {camera}"});
  refused({"-o", dir.file("v_{camera}.png")}, {"-o", "holds {camera} but no --camera"});
  refused({"--camera", "0,3", "-o", dir.file("v_{camera}.png")}, {"--camera", "camera 3 out of range", "has 3 cameras"});
  refused({"--camera", "1,1", "-o", dir.file("v_{camera}.png")}, {"--camera", "listed twice"});
  refused({"--camera", "1,", "-o", dir.file("v_{camera}.png")}, {"--camera", "a list of them (0,2,5) or all"});
  refused({"--camera", "every", "-o", dir.file("v_{camera}.png")}, {"--camera", "'every'"});
  refused({"--camera", "all", "-o", dir.file("v_{camera}.png"), "--checkpoint", dir.file("c.ckpt")},
          {"--checkpoint", "one view"});
  refused({"--camera", "all", "-o", dir.file("v_{camera}.png"), "--look-from", "0,1,5"}, {"--look-from", "--camera N"});
  // A view whose name cannot be written stops the whole batch before the first render.
  refused({"--camera", "all", "-o", dir.file("{camera}/v.png")}, {"0/v.png"});
  dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const CliResult obj = runMontecl({"render", dir.file("plain.obj"), "--camera", "all", "-o", dir.file("v_{camera}.png"), "-q"});
  checkRefused(obj, out, {"--camera", "all: no camera to render", "has 0 cameras"});
}

}  // namespace test_file_cli_batch
