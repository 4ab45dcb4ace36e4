// test_util.cpp: host/util: FNV hashing and atomic file writes.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/hash.h"

namespace test_file_util {  // keeps this file's helpers apart in a unity batch

namespace fs = std::filesystem;
using namespace montecl;

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {



}  // namespace

TEST_CASE("util: fnv1a64 and hex64" * doctest::test_suite("cpu")) {
  CHECK(fnv1a64("") == 0xcbf29ce484222325ull);
  CHECK(fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  CHECK(fnv1a64("foobar") == 0x85944171f73967e8ull);
  CHECK(fnv1a64("a") != fnv1a64("b"));
  CHECK(fnv1a64("a", 1) != fnv1a64("a"));
  Fnv1a64 pieces;  // fed piece by piece: the hash of the concatenation
  pieces.add("foo");
  pieces.add("", 0);
  pieces.add("bar", 3);
  CHECK(pieces.value() == fnv1a64("foobar"));
  CHECK(Fnv1a64(1).value() == 1u);
  CHECK(hex64(0x1234) == "0000000000001234");
  CHECK(hex64(0xaf63dc4c8601ec8cull) == "af63dc4c8601ec8c");
}

TEST_CASE("util: writeAtomically renames on success and cleans up on failure" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::string target = dir.file("out.png");

  std::string seenTmp;
  writeAtomically(target, [&](const std::string& tmp) {
    seenTmp = tmp;
    CHECK(tmp != target);
    CHECK(fs::path(tmp).parent_path() == fs::path(target).parent_path());
    CHECK(fs::path(tmp).extension() == ".png");
    std::ofstream(tmp) << "new";
  });
  CHECK(readAll(target) == "new");
  CHECK_FALSE(fs::exists(seenTmp));
  CHECK(dir.entries() == std::vector<std::string>{"out.png"});

  // Two writes get different temporary names.
  std::string secondTmp;
  writeAtomically(target, [&](const std::string& tmp) {
    secondTmp = tmp;
    std::ofstream(tmp) << "newer";
  });
  CHECK(secondTmp != seenTmp);
  CHECK(readAll(target) == "newer");

  // A failing writer leaves an existing target untouched and no temporary behind.
  CHECK_THROWS_WITH(writeAtomically(target,
                                    [&](const std::string& tmp) {
                                      std::ofstream(tmp) << "partial";
                                      throw std::runtime_error("writer failed");
                                    }),
                    "writer failed");
  CHECK(readAll(target) == "newer");
  CHECK(dir.entries() == std::vector<std::string>{"out.png"});

  // ... and creates nothing when there was no target.
  const std::string fresh = dir.file("fresh.exr");
  CHECK_THROWS_AS(writeAtomically(fresh,
                                  [&](const std::string& tmp) {
                                    std::ofstream(tmp) << "partial";
                                    throw RuntimeError("disk full");
                                  }),
                  RuntimeError);
  CHECK_FALSE(fs::exists(fresh));
  CHECK(dir.entries() == std::vector<std::string>{"out.png"});

  // A writer that produces no file is an error, not a silent success.
  CHECK_THROWS_AS(writeAtomically(dir.file("never.txt"), [](const std::string&) {}),
                  RuntimeError);
  CHECK(dir.entries() == std::vector<std::string>{"out.png"});
}

TEST_CASE("util: writeAtomically defers SIGTERM/SIGINT until the file is complete: no temporary is left" * doctest::test_suite("cpu")) {
  // A child process is signalled in the middle of its write (default dispositions: the signal
  // kills it). The signal must land only after the rename: the target complete, no temporary.
  for (int sig : {SIGTERM, SIGINT}) {
    TempDir dir;
    const std::string target = dir.file("out.png");
    pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      ::signal(sig, SIG_DFL);
      writeAtomically(target, [&](const std::string& tmp) {
        std::ofstream(tmp) << "half";
        ::raise(sig);
        std::ofstream(tmp, std::ios::app) << "-done";
      });
      ::_exit(0);
    }
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    INFO("signal " << sig);
    CHECK(WIFSIGNALED(status));  // still killed by the signal, after the write
    CHECK(readAll(target) == "half-done");
    CHECK(dir.entries() == std::vector<std::string>{"out.png"});
  }
}

TEST_CASE("util: writeAtomically removes temporaries of its target left by dead processes, nothing else" * doctest::test_suite("cpu")) {
  TempDir dir;
  pid_t dead = ::fork();
  REQUIRE(dead >= 0);
  if (dead == 0) ::_exit(0);
  REQUIRE(::waitpid(dead, nullptr, 0) == dead);  // a PID that no longer runs
  const std::string alive = std::to_string(::getppid());
  const std::vector<std::string> keep = {
      "." + std::string("out.png.tmp") + alive + "_0.png",            // a running process's
      ".other.png.tmp" + std::to_string(dead) + "_0.png",             // another target's
      ".out.png.tmp" + std::to_string(dead) + "_0.png.bak",           // not our pattern
      "out.png.tmp" + std::to_string(dead) + "_0.png"};               // not hidden
  const std::vector<std::string> stale = {tempFileName("out.png", dead, 0), tempFileName("out.png", dead, 17)};
  for (const auto& n : keep) std::ofstream(dir.file(n)) << "x";
  for (const auto& n : stale) std::ofstream(dir.file(n)) << "x";
  CHECK(stale[0] == ".out.png.tmp" + std::to_string(dead) + "_0.png");
  writeAtomically(dir.file("out.png"), [](const std::string& tmp) { std::ofstream(tmp) << "new"; });
  std::vector<std::string> expect = keep;
  expect.push_back("out.png");
  std::sort(expect.begin(), expect.end());
  CHECK(dir.entries() == expect);
}

TEST_CASE("util: temporary names fit NAME_MAX; checkWritableTarget refuses what cannot be written" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::string longName = std::string(250, 'a') + ".png";  // 254 bytes: legal
  CHECK(tempFileName(longName, 4194304, 123456).size() <= 255);
  CHECK(fs::path(tempFileName(longName, 4194304, 123456)).extension() == ".png");
  checkWritableTarget(dir.file(longName));
  writeAtomically(dir.file(longName), [](const std::string& tmp) { std::ofstream(tmp) << "ok"; });
  CHECK(readAll(dir.file(longName)) == "ok");
  CHECK(dir.entries() == std::vector<std::string>{longName});

  const std::string tooLong = dir.file(std::string(252, 'b') + ".png");
  CHECK_THROWS_AS(checkWritableTarget(tooLong), InputError);
  CHECK_THROWS_AS(checkWritableTarget(dir.file("missing/out.png")), InputError);
  CHECK_THROWS_AS(checkWritableTarget(dir.path), InputError);                // a folder
  CHECK_THROWS_AS(checkWritableTarget("/proc/montecl-out.png"), InputError);  // no file can be created there
  try {
    checkWritableTarget(tooLong);
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find(tooLong) == 0);  // names the output
  }
  CHECK(dir.entries() == std::vector<std::string>{longName});  // the probe leaves nothing
}

}  // namespace test_file_util
