// test_cli_view_env.cpp: the command line's --env (a constant or a map replacing the scene's
// environment) and --view (the automatic framing from another side), through the real command:
// a constant --env lights a bare model as the same environment in a scene file does (bit for bit);
// each --view sees the model (it fills the frame) and differs from the front; bad values are one
// line, exit 2; a bare model's defaults (path under the white sky) equal a scene file that writes
// them out with "camera": "auto".
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"

namespace test_file_cli_view_env {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {

// An open box (five faces of the unit cube): every side sees something else.
const char* kBox =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 4 3 7 8\n";

std::vector<std::string> args(const TempDir& dir, const std::string& in, const std::string& out) {
  return {"render", dir.file(in), "-o", dir.file(out), "--width", "16", "--height", "16", "--spp", "2", "-q",
          "--overwrite", "--aov", "depth"};
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<float> plane(const std::string& exr, const char* name) { return *montecl::readLayeredImage(exr).find(name); }

}  // namespace

TEST_CASE("cli: --env lights a bare model as a scene file's environment does; --view frames it from each side" *
          doctest::test_suite("cli sanitize")) {
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

TEST_CASE("cli: a bare model path-traces under the default white sky, as a scene file with camera \"auto\" says; "
          "--integrator ao renders AO as a scene file does" *
          doctest::test_suite("cli")) {
  TempDir dir;
  dir.write("box.obj", kBox);
  const auto render = [&](const std::string& in, const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> a = {"render", dir.file(in), "-o", dir.file(out), "--width", "16", "--height", "12",
                                  "--spp", "2", "--device", "host", "-q", "--overwrite"};
    a.insert(a.end(), extra.begin(), extra.end());
    const CliResult r = runMontecl(a);
    INFO(in << ": " << r.err);
    CHECK(r.exitCode == 0);
    return r;
  };
  const std::string mesh = R"("meshes": [{"file": "box.obj"}])";
  // The documented rule written out: integrator path, a constant environment of radiance 1.
  dir.write("sky.json", R"({"camera": "auto", )" + mesh +
                            R"(, "render": {"integrator": "path"}, "environment": {"radiance": [1, 1, 1]}})");
  dir.write("ao.json", R"({"camera": "auto", )" + mesh + "}");
  const CliResult bare = render("box.obj", "bare.pfm", {});
  CHECK(bare.err.find("warning") == std::string::npos);  // nothing to warn: it is lit
  render("sky.json", "sky.pfm", {});
  CHECK(fileText(dir.file("bare.pfm")) == fileText(dir.file("sky.pfm")));
  render("box.obj", "bare-ao.pfm", {"--integrator", "ao"});
  render("ao.json", "ao.pfm", {});
  CHECK(fileText(dir.file("bare-ao.pfm")) == fileText(dir.file("ao.pfm")));
  CHECK(fileText(dir.file("bare-ao.pfm")) != fileText(dir.file("bare.pfm")));
  // --env replaces the default sky.
  render("box.obj", "dim.pfm", {"--env", "0.25,0.25,0.25"});
  CHECK(fileText(dir.file("dim.pfm")) != fileText(dir.file("bare.pfm")));
}

}  // namespace test_file_cli_view_env
