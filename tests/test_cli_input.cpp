// test_cli_input.cpp: command-line input rules of `montecl render` (host/cli/validators.h): every
// numeric option is checked before any work, with a short message (no 300-digit bounds), NaN and
// infinity are refused, and the image size and light samples follow the scene file's limits.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <filesystem>
#include <regex>
#include <thread>

#include "cli_runner.h"

using montecl_test::CliResult;
using montecl_test::runMontecl;
using montecl_test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kGoodScene = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json";

// `montecl render <good scene> -o tmp/out.png <option> <value>`: exit 2, the message, no output.
std::string badOption(const std::string& option, const std::string& value) {
  TempDir dir;
  CliResult r = runMontecl({"render", kGoodScene, "-q", "-o", dir.file("out.png"), option, value});
  INFO(option << " " << value << ": stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(!fs::exists(dir.file("out.png")));
  CHECK(r.err.find(option) != std::string::npos);
  CHECK(!std::regex_search(r.err, std::regex("[0-9]{20}")));  // no 300-digit bounds
  return r.err;
}

}  // namespace

TEST_CASE("cli: integer options out of range say 'must be a positive integer'" * doctest::test_suite("cli")) {
  for (const char* opt : {"--spp", "--width", "--height", "--light-samples", "--wave-size", "--work-group-size"})
    for (const char* value : {"0", "-3", "1.5", "nan"}) {
      std::string err = badOption(opt, value);
      CHECK_MESSAGE(err.find("must be a positive integer") != std::string::npos, opt << " " << value << ": " << err);
    }
}

TEST_CASE("cli: float options refuse zero, NaN and infinity: 'must be a positive number'" * doctest::test_suite("cli")) {
  for (const char* opt : {"--ao-distance", "--target-error", "--time"})
    for (const char* value : {"0", "-1", "nan", "NaN", "inf", "-inf", "1e999"}) {
      std::string err = badOption(opt, value);
      CHECK_MESSAGE(err.find("must be a positive number") != std::string::npos, opt << " " << value << ": " << err);
    }
  // --ao-distance is a float: a double beyond the float range would become inf.
  CHECK(badOption("--ao-distance", "1e39").find("up to 3.40282e+38") != std::string::npos);
}

TEST_CASE("cli: --width/--height follow the scene file's 16384 cap; --light-samples its 1024 cap" * doctest::test_suite("cli")) {
  CHECK(badOption("--width", "16385").find("up to 16384") != std::string::npos);
  CHECK(badOption("--height", "20000").find("up to 16384") != std::string::npos);
  CHECK(badOption("--light-samples", "1025").find("up to 1024") != std::string::npos);
  CHECK(badOption("--light-samples", "1000000").find("up to 1024") != std::string::npos);
  // The largest allowed values pass the option check (tiny render: the other side stays small).
  TempDir dir;
  CliResult r = runMontecl({"render", kGoodScene, "-q", "-o", dir.file("out.png"), "--width", "16384", "--height",
                            "1", "--spp", "1", "--integrator", "direct", "--light-samples", "1024"});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 0);
}

TEST_CASE("cli: an mtllib that is a FIFO is refused at once, not opened (which would block)" * doctest::test_suite("cli")) {
  TempDir dir;
  REQUIRE(::mkfifo(dir.file("fifo.mtl").c_str(), 0600) == 0);
  dir.write("model.obj", "mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  // A montecl that opens the FIFO blocks until a writer comes: this thread is that writer after
  // 5 s (then the reader sees an empty file and renders), so the test ends either way.
  std::atomic<bool> done{false};
  std::thread writer([&] {
    auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!done && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    while (!done) {
      int fd = ::open(dir.file("fifo.mtl").c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) {
        ::close(fd);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  const auto start = std::chrono::steady_clock::now();
  CliResult r = runMontecl({"render", dir.file("model.obj"), "-q", "--spp", "1", "--width", "8", "--height", "8",
                            "-o", dir.file("out.png")});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  done = true;
  writer.join();
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(seconds < 5.0);
  CHECK(r.err.find("fifo.mtl': not a regular file") != std::string::npos);
  CHECK(!fs::exists(dir.file("out.png")));
}
