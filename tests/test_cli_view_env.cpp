// test_cli_view_env.cpp: the command line's --env (a constant or a map replacing the scene's
// environment) and --view (the automatic framing from another side), through the real command:
// a constant --env lights a bare model as the same environment in a scene file does (bit for bit);
// each --view sees the model (it fills the frame) and differs from the front; bad values are one
// line, exit 2.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"

using montecl_test::CliResult;
using montecl_test::runMontecl;
using montecl_test::TempDir;

namespace {

// An open box (five faces of the unit cube): every side sees something else.
const char* kBox =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 4 3 7 8\n";

std::vector<std::string> args(const TempDir& dir, const std::string& in, const std::string& out) {
  return {"render", dir.file(in), "-o", dir.file(out), "--width", "16", "--height", "16", "--spp", "2", "-q",
          "--overwrite", "--aov", "depth"};
}

std::vector<float> plane(const std::string& exr, const char* name) { return *montecl::readLayeredImage(exr).find(name); }

}  // namespace

TEST_CASE("cli: --env lights a bare model as a scene file's environment does; --view frames it from each side" *
          doctest::test_suite("cli")) {
  TempDir dir;
  dir.write("box.obj", kBox);
  // A constant given directly and as 2x the radiance at --env-scale 0.5 light the same image.
  std::vector<std::string> a = args(dir, "box.obj", "env.exr");
  a.insert(a.end(), {"--integrator", "direct", "--env", "0.5,0.75,1"});
  const CliResult env = runMontecl(a);
  INFO(env.err);
  REQUIRE(env.exitCode == 0);
  CHECK(env.err.find("nothing emits") == std::string::npos);  // the environment lights it
  std::vector<std::string> b = a;
  b.back() = "1,1.5,2";
  b.insert(b.end(), {"--env-scale", "0.5"});
  b[3] = dir.file("scaled.exr");
  REQUIRE(runMontecl(b).exitCode == 0);
  CHECK(plane(dir.file("env.exr"), "R") == plane(dir.file("scaled.exr"), "R"));  // 0.5 x (1, 1.5, 2) = the same
  const std::vector<float> lit = plane(dir.file("env.exr"), "G");
  CHECK(*std::max_element(lit.begin(), lit.end()) > 0.0f);

  // Each side: the model fills part of the frame (finite depth somewhere) and the depth image
  // differs from the front's.
  const std::vector<std::string> sides = {"front", "back", "left", "right", "top", "bottom", "iso"};
  std::vector<std::vector<float>> depth;
  for (const std::string& side : sides) {
    std::vector<std::string> v = args(dir, "box.obj", side + ".exr");
    v.insert(v.end(), {"--view", side});
    const CliResult r = runMontecl(v);
    INFO(side << ": " << r.err);
    REQUIRE(r.exitCode == 0);
    depth.push_back(plane(dir.file(side + ".exr"), "Z"));
    const auto hits = std::count_if(depth.back().begin(), depth.back().end(), [](float z) { return std::isfinite(z) && z > 0; });
    CHECK(hits > 16 * 16 / 4);
  }
  for (std::size_t i = 1; i < sides.size(); ++i) {
    INFO(sides[i]);
    CHECK(depth[i] != depth[0]);
  }
  // front is what a bare mesh gets without --view.
  REQUIRE(runMontecl(args(dir, "box.obj", "plain.exr")).exitCode == 0);
  CHECK(plane(dir.file("plain.exr"), "Z") == depth[0]);

  // Bad values: one line, exit 2, no file.
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--view", "sideways"}, {"--env", "1,-1,1"}, {"--env", dir.file("no-such.exr")},
        {"--env", "1,1,1", "--env-scale", "-2"}}) {
    std::vector<std::string> v = args(dir, "box.obj", "bad.exr");
    v.insert(v.end(), bad.begin(), bad.end());
    const CliResult r = runMontecl(v);
    INFO(bad[0] << " " << bad[1] << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(bad[0] == "--env" && bad.size() > 2 ? "--env-scale" : bad[0]) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("bad.exr")));
  }
}
