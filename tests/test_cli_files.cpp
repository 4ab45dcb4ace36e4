// test_cli_files.cpp: `montecl render` and its files and signals, end to end: SIGTERM stops a
// render like SIGINT (exit 143), an inherited "ignore SIGINT" stays ignored, a signal during the
// image write of a complete render changes nothing (exit 0), the output may not be one of the
// render's inputs, an unwritable output fails before the render (exit 2), and emission that
// overflows a float is refused at load (exit 2) or, where it still overflows, no NaN/inf image is
// written (exit 1).
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli_runner.h"
#include "image/exr_layers.h"


namespace test_file_cli_files {  // keeps this file's helpers apart in a unity batch

using montecl::LayeredImage;
using montecl::readLayeredImage;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
const auto& entries = montecl_test::folderEntries;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> longRender(const std::string& out) {
  return {"render", montecl_test::demoScene(), "-o", out, "--width", "64", "--height", "48", "--spp", "1000000",
          "--wave-size", "20000", "-q"};
}

void checkPartialImage(const std::string& path) {
  LayeredImage img = readLayeredImage(path);
  CHECK(img.width == 64);
  const std::vector<float>& n = *img.find("samples");
  float lo = *std::min_element(n.begin(), n.end()), hi = *std::max_element(n.begin(), n.end());
  CHECK(lo >= 1.0f);
  CHECK(hi < 1000000.0f);
}

// A floor and a small lamp 1 mm above it: emission 3.4e38 passes the load check (lamp power is
// finite) but the light's contributions overflow a float.
void writeLampScene(const TempDir& dir, const std::string& emission) {
  dir.write("floor.obj", "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 3 2\nf 1 4 3\nf 1 2 3\nf 1 3 4\n");
  dir.write("lamp.obj", "v -0.4 0.001 -0.4\nv 0.4 0.001 -0.4\nv 0.4 0.001 0.4\nv -0.4 0.001 0.4\nf 1 2 3\nf 1 3 4\n");
  dir.write("scene.json",
            "{\"camera\": {\"position\": [0, 2, 3], \"target\": [0, 0, 0], \"up\": [0, 1, 0], \"fov_y\": 40, "
            "\"width\": 16, \"height\": 12},\n \"meshes\": [{\"file\": \"floor.obj\"}, {\"file\": \"lamp.obj\", "
            "\"emission\": [" + emission + ", " + emission + ", " + emission + "]}],\n"
            " \"render\": {\"integrator\": \"direct\", \"spp\": 16, \"direct_sampling\": \"mis\"}}\n");
}

}  // namespace

TEST_CASE("cli: SIGTERM finishes the wave, writes the image so far, exits 143" * doctest::test_suite("cli sanitize slow")) {
  TempDir dir, log;
  std::vector<std::string> args = longRender(dir.file("t.exr"));
  args.push_back("-v");
  pid_t pid = spawnMontecl(args, log.file("err.txt"));
  // The waves have begun once -v has printed the wave plan (kernels built, handler installed);
  // the message is checked below, so a changed wording fails instead of waiting out the minute.
  for (int i = 0; i < 1200 && readAll(log.file("err.txt")).find("montecl: waves of") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(readAll(log.file("err.txt")).find("montecl: waves of") != std::string::npos);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGTERM);
  CHECK(waitFor(pid) == 143);
  checkPartialImage(dir.file("t.exr"));
  CHECK(entries(dir.path) == std::vector<std::string>{"t.exr"});
}

TEST_CASE("cli: an inherited SIG_IGN for SIGINT stays ignored (background jobs)" * doctest::test_suite("cli sanitize slow")) {
  TempDir dir;
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  REQUIRE(sigaction(SIGINT, &ignore, &previous) == 0);
  pid_t pid = spawnMontecl(longRender(dir.file("bg.exr")));  // inherits SIGINT ignored, like `cmd &` in a script
  sigaction(SIGINT, &previous, nullptr);
  // SIGINT every 100 ms for 4 s: while the kernels build and while the waves run.
  for (int i = 0; i < 40; ++i) {
    kill(pid, SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  int status = 0;
  const bool stillRunning = waitpid(pid, &status, WNOHANG) == 0;
  CHECK(stillRunning);
  if (stillRunning) {
    kill(pid, SIGTERM);
    CHECK(waitFor(pid) == 143);
  }
}

TEST_CASE("cli: a SIGINT while a complete render is being written exits 0 with the full image" * doctest::test_suite("cli sanitize slow")) {
  // A big EXR with every AOV takes a while to compress and write; the render itself is short. The
  // signal is sent as soon as the temporary file has data, i.e. after the last wave.
  TempDir dir;
  const std::string out = dir.file("w.exr");
  pid_t pid = spawnMontecl({"render", montecl_test::demoScene(), "-o", out, "--width", "1600", "--height", "1200",
                            "--spp", "1", "--aov", "all", "-q"});
  bool sent = false;
  for (int i = 0; i < 60000 && !sent; ++i) {
    std::error_code ec;
    for (const std::string& name : entries(dir.path))  // an empty one may be the writability probe
      if (name.rfind(".w.exr.tmp", 0) == 0 && fs::file_size(dir.file(name), ec) > 0 && !ec) {
        kill(pid, SIGINT);
        sent = true;
        break;
      }
    if (!sent) {
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) FAIL("montecl ended before its image write was seen");
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }
  REQUIRE(sent);
  CHECK(waitFor(pid) == 0);
  LayeredImage img = readLayeredImage(out);
  const std::vector<float>& n = *img.find("samples");
  CHECK(*std::min_element(n.begin(), n.end()) == 1.0f);
  CHECK(entries(dir.path) == std::vector<std::string>{"w.exr"});
}

TEST_CASE("cli: an output that is one of the render's inputs is refused (exit 2), the input untouched" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string obj = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/quad.obj";
  const std::string mtl = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/quad.mtl";
  const std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json";
  const std::string objBefore = readAll(obj), mtlBefore = readAll(mtl), sceneBefore = readAll(scene);
  struct Case {
    std::string input, linkTo;
  };
  for (const Case& c : {Case{obj, obj}, Case{obj, mtl}, Case{scene, scene}, Case{scene, obj}}) {
    INFO("render " << c.input << " -o link to " << c.linkTo);
    const std::string out = dir.file("out.png");
    fs::remove(out);
    fs::create_symlink(c.linkTo, out);
    CliResult r = runMontecl({"render", c.input, "-o", out, "--width", "8", "--height", "8", "--spp", "1", "-q"});
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find("out.png") != std::string::npos);
    CHECK(r.err.find("input") != std::string::npos);
  }
  CHECK(readAll(obj) == objBefore);
  CHECK(readAll(mtl) == mtlBefore);
  CHECK(readAll(scene) == sceneBefore);
}

TEST_CASE("cli: an output that cannot be written fails before the render (exit 2); a 254-byte name works" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = montecl_test::demoScene();
  for (const std::string& out : {dir.file(std::string(256, 'n') + ".png"), std::string("/proc/montecl-out.png"),
                                 dir.file("no-folder/out.png")}) {
    INFO("output " << out);
    // The device spec is bad too: the output is checked before the device is chosen and any work.
    CliResult r = runMontecl({"render", scene, "-o", out, "--spp", "1", "-q", "--device", "9:9"});
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(out) != std::string::npos);
  }
  const std::string longName = dir.file(std::string(250, 'l') + ".png");
  CliResult r = runMontecl({"render", scene, "-o", longName, "--width", "8", "--height", "8", "--spp", "1", "-q"});
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(entries(dir.path) == std::vector<std::string>{std::string(250, 'l') + ".png"});
}

TEST_CASE("cli: emission whose luminance x area overflows a float is refused at load, naming the material" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("big.json", "{\"camera\": {\"position\": [0, 1, 5], \"target\": [0, 0, 0], \"up\": [0, 1, 0], \"fov_y\": 40, \"width\": 8, \"height\": 8}, \"meshes\": [{\"file\": \"" + std::string(MONTECL_SOURCE_DIR) +
                            "/scenes/demo/demo.obj\", \"emission\": [3.4e38, 3.4e38, 3.4e38]}],"
                            " \"render\": {\"integrator\": \"direct\"}}");
  CliResult r = runMontecl({"render", dir.file("big.json"), "-o", dir.file("o.png"), "-q"});
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find("big.json") != std::string::npos);
  CHECK(r.err.find("emission") != std::string::npos);
  CHECK(r.err.find("material '") != std::string::npos);
  CHECK(!fs::exists(dir.file("o.png")));
}

TEST_CASE("cli: a render whose values overflow a float writes no image and exits 1 naming how many pixels" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeLampScene(dir, "3.4e38");
  CliResult r = runMontecl({"render", dir.file("scene.json"), "-o", dir.file("o.exr"), "-q"});
  CHECK(r.exitCode == 1);
  CHECK(oneLine(r.err));
  CHECK(r.err.find(" of 192 pixels") != std::string::npos);
  CHECK(!fs::exists(dir.file("o.exr")));
  // The same scene with a modest lamp renders.
  writeLampScene(dir, "10");
  r = runMontecl({"render", dir.file("scene.json"), "-o", dir.file("o.exr"), "-q"});
  CHECK(r.exitCode == 0);
}

}  // namespace test_file_cli_files
