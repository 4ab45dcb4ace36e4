// test_structure.cpp: the source tree's structure rules, read from the sources: host folders include
// only folders of lower layers (util < scene, image < bvh, texture < cl < render < bench, conformance,
// integrate, dist < cli < main), so no two folders depend on each other; kernels/shared (pure functions
// and the stage table) never includes the stage bodies (kernels/stages); no host source file
// is longer than 450 lines.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

namespace fs = std::filesystem;

namespace {

// Layer of a host folder; folders of one layer may not include each other.
const std::map<std::string, int>& hostLayers() {
  static const std::map<std::string, int> layers{
      {"util", 0},  {"scene", 1},       {"image", 1},     {"bvh", 2},       {"texture", 2},   {"cl", 3},
      {"render", 4}, {"bench", 5},      {"conformance", 5}, {"integrate", 5}, {"dist", 5},
      {"cli", 6},
  };
  return layers;
}

// The folders of `#include "folder/..."` lines in a file.
std::vector<std::string> includedFolders(const fs::path& file) {
  static const std::regex includeLine(R"re(^\s*#\s*include\s*"([^"/]+)/)re");
  std::vector<std::string> out;
  std::ifstream in(file);
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, includeLine)) out.push_back(m[1]);
  return out;
}

std::vector<fs::path> sourcesUnder(const fs::path& root) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".h" || ext == ".cpp" || ext == ".cl")) files.push_back(e.path());
  }
  return files;
}

}  // namespace

TEST_CASE("structure: every host include goes to a lower layer (or the kernels), none back up" * doctest::test_suite("cpu")) {
  const fs::path host = fs::path(MONTECL_SOURCE_DIR) / "host";
  int files = 0, violations = 0;
  for (const fs::path& file : sourcesUnder(host)) {
    const std::string folder = fs::relative(file, host).begin()->string();
    if (folder == file.filename().string()) continue;  // host/main.cpp: the top
    ++files;
    REQUIRE_MESSAGE(hostLayers().count(folder), "host/" << folder << " has no layer in this test");
    const int own = hostLayers().at(folder);
    for (const std::string& inc : includedFolders(file)) {
      if (inc == folder || inc == "kernels") continue;
      auto it = hostLayers().find(inc);
      const bool ok = it != hostLayers().end() && it->second < own;
      if (!ok) {
        ++violations;
        MESSAGE(fs::relative(file, host).string() << " includes " << inc << "/ (layer "
                << (it == hostLayers().end() ? -1 : it->second) << ", its own " << own << ")");
      }
    }
  }
  CHECK(files > 50);
  CHECK(violations == 0);
}

TEST_CASE("structure: kernels/shared never includes the stage bodies" * doctest::test_suite("cpu")) {
  const fs::path shared = fs::path(MONTECL_SOURCE_DIR) / "kernels" / "shared";
  int violations = 0;
  for (const fs::path& file : sourcesUnder(shared)) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line))
      if (line.find("#include") != std::string::npos && line.find("stages/") != std::string::npos) {
        ++violations;
        MESSAGE(file.filename().string() << ": " << line);
      }
  }
  CHECK(violations == 0);
}

TEST_CASE("structure: no host source file is over 450 lines" * doctest::test_suite("cpu")) {
  const fs::path host = fs::path(MONTECL_SOURCE_DIR) / "host";
  int longFiles = 0;
  for (const fs::path& file : sourcesUnder(host)) {
    std::ifstream in(file);
    int lines = 0;
    std::string line;
    while (std::getline(in, line)) ++lines;
    if (lines > 450) {
      ++longFiles;
      MESSAGE(fs::relative(file, host).string() << ": " << lines << " lines");
    }
  }
  CHECK(longFiles == 0);
}
