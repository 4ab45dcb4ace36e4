// test_cli_render.cpp: end-to-end bad-input tests through the real command line: every case under
// scenes/test/bad/ (and a missing scene file, a bad --device) makes `montecl render` exit with 2,
// print exactly one stderr line naming the file and key/line, and create no output file.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "cli_runner.h"

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

TEST_CASE("cli: every bad scene under scenes/test/bad exits 2 with one line naming file and key") {
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

TEST_CASE("cli: a missing scene file exits 2 naming it") {
  TempDir dir;
  std::string err = renderExpectingBadInput(dir.file("no-such-scene.json"));
  CHECK(err.find("no-such-scene.json") != std::string::npos);
}

TEST_CASE("cli: a bad --device spec exits 2") {
  std::string err = renderExpectingBadInput(kScenes + "/good/scene.json", {"--device", "9:9"});
  std::transform(err.begin(), err.end(), err.begin(), [](unsigned char c) { return std::tolower(c); });
  CHECK(err.find("device") != std::string::npos);
}
