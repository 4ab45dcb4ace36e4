// test_util.cpp: host/util: FNV hashing and atomic file writes.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/hash.h"

namespace fs = std::filesystem;
using namespace montecl;

namespace {

// A fresh temporary folder, removed with everything in it at the end of the test.
struct ScratchDir {
  std::string path;
  ScratchDir() {
    std::string tmpl = (fs::temp_directory_path() / "montecl_test_cl_XXXXXX").string();
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    REQUIRE(::mkdtemp(buf.data()) != nullptr);
    path = buf.data();
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return path + "/" + name; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("util: fnv1a64 and hex64" * doctest::test_suite("cpu")) {
  CHECK(fnv1a64("") == 0xcbf29ce484222325ull);
  CHECK(fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  CHECK(fnv1a64("foobar") == 0x85944171f73967e8ull);
  CHECK(fnv1a64("a") != fnv1a64("b"));
  CHECK(fnv1a64("a", 1) != fnv1a64("a"));
  CHECK(hex64(0x1234) == "0000000000001234");
  CHECK(hex64(0xaf63dc4c8601ec8cull) == "af63dc4c8601ec8c");
}

TEST_CASE("util: writeAtomically renames on success and cleans up on failure" * doctest::test_suite("cpu")) {
  ScratchDir dir;
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
