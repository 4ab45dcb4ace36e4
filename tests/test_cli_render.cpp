// test_cli_render.cpp: `montecl render` (host/cli/cmd_render) through the real command line: every
// bad-input case under scenes/test/bad/ (and a missing scene file, a bad --device) exits with 2,
// prints exactly one stderr line naming the file and key/line, and creates no output file; --time
// and SIGINT stop a render and leave a valid image whose per-pixel sample counts are what was done.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_runner.h"
#include "image/exr_layers.h"

extern char** environ;

using montecl::LayeredImage;
using montecl::readLayeredImage;
using montecl_test::CliResult;
using montecl_test::runMontecl;
using montecl_test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kScenes = std::string(MONTECL_SOURCE_DIR) + "/scenes/test";

std::size_t entriesIn(const std::string& folder) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

// Runs `montecl render scene -o <tmp>/out.png [extra...]` in a fresh temp folder and checks the
// common contract of a bad-input failure; returns the one stderr line.
std::string renderExpectingBadInput(const std::string& scene, const std::vector<std::string>& extra = {}) {
  TempDir out;
  std::vector<std::string> args{"render", scene, "-o", out.file("out.png")};
  args.insert(args.end(), extra.begin(), extra.end());
  CliResult r = runMontecl(args);
  INFO("stderr: " << r.err);
  INFO("stdout: " << r.out);
  CHECK(r.exitCode == 2);
  CHECK(!r.err.empty());
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') <= 1);
  CHECK((r.err.empty() || r.err.find('\n') == r.err.size() - 1 || r.err.find('\n') == std::string::npos));
  CHECK(!fs::exists(out.file("out.png")));
  CHECK(entriesIn(out.path) == 0);  // no partial or temporary files either
  return r.err;
}

}  // namespace

TEST_CASE("cli: every bad scene under scenes/test/bad exits 2 with one line naming file and key" * doctest::test_suite("cli")) {
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(kScenes + "/bad")) cases.push_back(entry.path());
  std::sort(cases.begin(), cases.end());
  REQUIRE(cases.size() >= 40);
  for (const fs::path& dir : cases) {
    std::vector<std::string> expect = montecl_test::readLines((dir / "expect.txt").string());
    REQUIRE(expect.size() >= 2);
    INFO("case " << dir.filename().string());
    std::string err = renderExpectingBadInput((dir / expect[0]).string());
    for (std::size_t i = 1; i < expect.size(); ++i) {
      INFO("expected in stderr: " << expect[i] << "; stderr: " << err);
      CHECK(err.find(expect[i]) != std::string::npos);
    }
  }
}

TEST_CASE("cli: a missing scene file exits 2 naming it" * doctest::test_suite("cli")) {
  TempDir dir;
  std::string err = renderExpectingBadInput(dir.file("no-such-scene.json"));
  CHECK(err.find("no-such-scene.json") != std::string::npos);
}

TEST_CASE("cli: a bad --device spec exits 2" * doctest::test_suite("cli")) {
  std::string err = renderExpectingBadInput(kScenes + "/good/scene.json", {"--device", "9:9"});
  std::transform(err.begin(), err.end(), err.begin(), [](unsigned char c) { return std::tolower(c); });
  CHECK(err.find("device") != std::string::npos);
}

TEST_CASE("--time stops after the wave that crosses the limit and writes the image so far" * doctest::test_suite("cli")) {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  CliResult r = runMontecl({"render", scene, "-o", dir.file("t.exr"), "--width", "64", "--height", "48", "--spp",
                            "1000000", "--time", "1", "--wave-size", "20000", "-q"});
  INFO(r.out << r.err);
  REQUIRE(r.exitCode == 0);
  LayeredImage img = readLayeredImage(dir.file("t.exr"));
  const std::vector<float>& n = *img.find("samples");
  float lo = *std::min_element(n.begin(), n.end()), hi = *std::max_element(n.begin(), n.end());
  CHECK(lo >= 1.0f);
  CHECK(hi - lo <= 1.0f);  // sample-major waves: counts differ by at most one
  CHECK(hi < 1000000.0f);
}

TEST_CASE("SIGINT finishes the wave, writes a valid image with its true sample counts, exits 130" * doctest::test_suite("cli slow")) {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  std::string out = dir.file("i.exr");
  std::vector<std::string> args = {MONTECL_EXE, "render", scene, "-o", out, "--width", "64", "--height", "48",
                                   "--spp", "1000000", "--wave-size", "20000", "-q"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, MONTECL_EXE, &actions, nullptr, argv.data(), environ) == 0);
  posix_spawn_file_actions_destroy(&actions);
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  kill(pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  LayeredImage img = readLayeredImage(out);
  CHECK(img.width == 64);
  const std::vector<float>& n = *img.find("samples");
  float lo = *std::min_element(n.begin(), n.end()), hi = *std::max_element(n.begin(), n.end());
  CHECK(hi - lo <= 1.0f);
  CHECK(hi < 1000000.0f);
  // The mean is finite everywhere a sample was taken.
  for (float v : *img.find("R")) REQUIRE(std::isfinite(v));
}

TEST_CASE("cli: --min-spp above --max-spp exits 2 before any work" * doctest::test_suite("cli")) {
  // Checked first: the scene is missing and the device bad too, yet the error is about --min-spp.
  TempDir dir;
  std::string err = renderExpectingBadInput(dir.file("no-such-scene.json"), {"--target-error", "0.1", "--min-spp",
                                                                             "64", "--max-spp", "8", "--device", "9:9"});
  CHECK(err.find("--min-spp") != std::string::npos);
  CHECK(err.find("--max-spp (8)") != std::string::npos);
}
