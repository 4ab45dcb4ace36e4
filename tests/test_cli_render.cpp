// test_cli_render.cpp: `montecl render` (host/cli/cmd_render) through the real command line: every
// bad-input case under scenes/test/bad/ (and a missing scene file, a bad --device) exits with 2,
// prints exactly one stderr line naming the file and key/line, and creates no output file; --time
// and SIGINT stop a render and leave a valid image whose per-pixel sample counts are what was done.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/stat.h>
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
#include "skip.h"
#include "image/exr_layers.h"


namespace test_file_cli_render {  // keeps this file's helpers apart in a unity batch

using montecl::LayeredImage;
using montecl::readLayeredImage;
using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
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

TEST_CASE("cli: every bad scene under scenes/test/bad exits 2 with one line naming file and key" * doctest::test_suite("cli sanitize")) {
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

TEST_CASE("cli: a missing scene file exits 2 naming it" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  std::string err = renderExpectingBadInput(dir.file("no-such-scene.json"));
  CHECK(err.find("no-such-scene.json") != std::string::npos);
}

TEST_CASE("cli: a bad --device spec exits 2" * doctest::test_suite("cli sanitize")) {
  std::string err = renderExpectingBadInput(kScenes + "/good/scene.json", {"--device", "9:9"});
  std::transform(err.begin(), err.end(), err.begin(), [](unsigned char c) { return std::tolower(c); });
  CHECK(err.find("device") != std::string::npos);
}

TEST_CASE("--time stops after the wave that crosses the limit and writes the image so far" * doctest::test_suite("cli sanitize")) {
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
  CHECK(hi - lo <= 1.0f);  // a time limit walks one sample per pixel at a time: counts differ by at most one
  CHECK(hi < 1000000.0f);
}

TEST_CASE("SIGINT finishes the wave, writes a valid image with its true sample counts, exits 130" * doctest::test_suite("cli sanitize slow")) {
  TempDir dir;
  std::string scene = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json";
  std::string out = dir.file("i.exr");
  const pid_t pid = spawnMontecl({"render", scene, "-o", out, "--width", "64", "--height", "48", "--spp", "1000000",
                                  "--wave-size", "20000", "-q"});
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  kill(pid, SIGINT);
  CHECK(waitFor(pid) == 130);
  LayeredImage img = readLayeredImage(out);
  CHECK(img.width == 64);
  const std::vector<float>& n = *img.find("samples");
  float lo = *std::min_element(n.begin(), n.end()), hi = *std::max_element(n.begin(), n.end());
  CHECK(hi - lo <= 16.0f);  // at most one block of samples (up to 16, the widest packet)
  CHECK(hi < 1000000.0f);
  // The mean is finite everywhere a sample was taken.
  for (float v : *img.find("R")) REQUIRE(std::isfinite(v));
}

TEST_CASE("cli: --min-spp above --max-spp exits 2 before any work" * doctest::test_suite("cli sanitize")) {
  // Checked first: the scene is missing and the device bad too, yet the error is about --min-spp.
  TempDir dir;
  std::string err = renderExpectingBadInput(dir.file("no-such-scene.json"), {"--target-error", "0.1", "--min-spp",
                                                                             "64", "--max-spp", "8", "--device", "9:9"});
  CHECK(err.find("--min-spp") != std::string::npos);
  CHECK(err.find("--max-spp (8)") != std::string::npos);
}

// Program cache robustness: a damaged cache must never break a later run. Each case fails without
// the fix: a truncated or byte-flipped cache file crashed PoCL (exit 139) on every later run, a FIFO blocked (timeout), and
// XDG_CACHE_HOME under a regular file made PoCL report "no OpenCL device found" (exit 1).
// Not `sanitize`: its time is PoCL rebuilding the kernels after each damage (77 s under ASan); the
// cache entries' host code runs sanitized in the cpu case "fuzz: 10k mutated program-cache entries".
TEST_CASE("cli: a damaged, odd or unwritable program cache never crashes, hangs or hides the device" * doctest::test_suite("cli")) {
  namespace fs = std::filesystem;
  TempDir dir;
  const std::string cache = dir.file("cache");
  const std::vector<std::string> env = {"MONTECL_CACHE_DIR=" + cache, "POCL_CACHE_DIR=" + dir.file("pocl")};
  const auto render = [&](const std::vector<std::string>& e) {
    return runMontecl(montecl_test::demoRenderArgs(dir.file("out.png"), 1, 0), e);
  };
  CliResult first = render(env);
  REQUIRE(first.exitCode == 0);
  std::vector<fs::path> bins;
  for (const auto& entry : fs::directory_iterator(cache)) bins.push_back(entry.path());
  REQUIRE(bins.size() == 1);
  const fs::path bin = bins[0];
  const auto size = fs::file_size(bin);
  REQUIRE(size > 1000);
  // Truncated, then one flipped byte in the middle: rebuilt and rewritten whole.
  fs::resize_file(bin, size / 2);
  CliResult truncated = render(env);
  CHECK(truncated.exitCode == 0);
  CHECK(fs::file_size(bin) > size / 2);  // rewritten whole (PoCL binaries vary a little in size)
  {
    std::fstream f(bin, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(size / 2));
    f.put(char(0x5a ^ 0xff));
    f.seekp(std::streamoff(size * 3 / 4));
    f.put(char(0x00));
  }
  CliResult flipped = render(env);
  CHECK(flipped.exitCode == 0);
  CHECK(flipped.err.find("warning") == std::string::npos);
  // The cache file is a folder, a FIFO, /dev/zero: skipped with one warning.
  for (const std::string kind : {"directory", "FIFO", "/dev/zero"}) {
    CAPTURE(kind);
    fs::remove_all(bin);
    if (kind == "directory") fs::create_directory(bin);
    else if (kind == "FIFO") REQUIRE(::mkfifo(bin.c_str(), 0600) == 0);
    else fs::create_symlink("/dev/zero", bin);
    CliResult r = render(env);
    CHECK(r.exitCode == 0);
    CHECK(r.err.find("warning: program cache") != std::string::npos);
  }
  // XDG_CACHE_HOME (PoCL's cache and ours) below a regular file: renders, says where PoCL's went.
  CliResult ro = render({"XDG_CACHE_HOME=/etc/hostname/x", "MONTECL_CACHE_DIR=", "POCL_CACHE_DIR="});
  CHECK(ro.exitCode == 0);
  CHECK(ro.err.find("PoCL's kernel cache is in") != std::string::npos);
}

// Oclgrind: montecl adds -cl-opt-disable itself on the Oclgrind platform. Without it
// Debian's Oclgrind 21.10 aborts (SIGSEGV) on LLVM `freeze` in the optimised kernels unless the
// user sets OCLGRIND_BUILD_OPTIONS=-cl-opt-disable.
TEST_CASE("cli: oclgrind montecl render --device oclgrind works without OCLGRIND_BUILD_OPTIONS" * doctest::test_suite("cli sanitize")) {
  MCL_SKIP_UNLESS(std::ifstream("/usr/bin/oclgrind").good(), "oclgrind is not installed");
  TempDir dir;
  CliResult r = montecl_test::runProgram(
      {"oclgrind", MONTECL_EXE, "render", std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json", "--device",
       "oclgrind", "--spp", "1", "--width", "8", "--height", "6", "--quiet", "-o", dir.file("o.png")},
      {"OCLGRIND_BUILD_OPTIONS=", "MONTECL_CACHE_DIR=" + dir.file("cache")});
  INFO(r.err);
  CHECK(r.exitCode == 0);
}

}  // namespace test_file_cli_render
