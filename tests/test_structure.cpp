// test_structure.cpp: the source tree's structure rules, read from the sources: host folders include
// only folders of lower layers (util < scene, image < bvh, texture < cl < render < bench, conformance,
// integrate, job < cli < main), so no two folders depend on each other; kernels/shared (pure functions
// and the stage table) never includes the stage bodies (kernels/stages); no host source file
// is longer than 450 lines, no function in host/render longer than 120; every stage of the stage
// table runs in some case of the conformance set (so `montecl conformance` checks every stage body).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "conformance/scenes.h"
#include "cli_runner.h"
#include "render/wavefront.h"

namespace test_file_structure {  // keeps this file's helpers apart in a unity batch

namespace fs = std::filesystem;

namespace {

// Layer of a host folder; folders of one layer may not include each other.
const std::map<std::string, int>& hostLayers() {
  static const std::map<std::string, int> layers{
      {"util", 0},  {"scene", 1},       {"image", 1},     {"bvh", 2},       {"texture", 2},   {"cl", 3},
      {"render", 4}, {"bench", 5},      {"conformance", 5}, {"integrate", 5}, {"job", 5},
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

namespace {

// Lines of each function body in a C++ file, found by brace depth: a block opened at the top level
// (outside namespaces), or inside a class/struct body, that is not itself a class, struct, enum or
// namespace. Comments and string literals are blanked first. Returns (first line, lines) pairs.
std::vector<std::pair<int, int>> functionLengths(const fs::path& file) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string code = text;
  for (std::size_t i = 0; i < code.size(); ++i) {  // blank // and /* */ comments, "..." and '...'
    if (code.compare(i, 2, "//") == 0) {
      while (i < code.size() && code[i] != '\n') code[i++] = ' ';
    } else if (code.compare(i, 2, "/*") == 0) {
      for (; i + 1 < code.size() && code.compare(i, 2, "*/") != 0; ++i)
        if (code[i] != '\n') code[i] = ' ';
    } else if (code[i] == '"' || code[i] == '\'') {
      const char quote = code[i];
      for (++i; i < code.size() && code[i] != quote; ++i) {
        if (code[i] == '\\') code[i++] = ' ';
        if (code[i] != '\n') code[i] = ' ';
      }
    }
  }
  struct Open {
    bool function;  // a function body (or an initializer/lambda inside one)
    bool scope;     // a namespace / class / struct / enum body: its blocks are at "top level"
    int line;
  };
  std::vector<Open> stack;
  std::vector<std::pair<int, int>> out;
  int line = 1;
  std::size_t statementStart = 0;
  static const std::regex scopeHead(R"re(\b(namespace|class|struct|enum|union)\b[^;()]*$)re");
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    if (c == '\n') ++line;
    if (c == ';' || c == '}') statementStart = i + 1;
    if (c == '{') {
      const bool insideFunction = !stack.empty() && !stack.back().scope;
      const std::string head = code.substr(statementStart, i - statementStart);
      const bool scope = !insideFunction && std::regex_search(head, scopeHead);
      stack.push_back({!insideFunction && !scope, scope, line});
      statementStart = i + 1;
    } else if (c == '}' && !stack.empty()) {
      const Open o = stack.back();
      stack.pop_back();
      if (o.function) out.push_back({o.line, line - o.line + 1});
    }
  }
  return out;
}

}  // namespace

TEST_CASE("structure: no function in host/render is over 120 lines" * doctest::test_suite("cpu")) {
  const fs::path render = fs::path(MONTECL_SOURCE_DIR) / "host" / "render";
  int functions = 0, longOnes = 0;
  for (const fs::path& file : sourcesUnder(render))
    for (const auto& [first, lines] : functionLengths(file)) {
      ++functions;
      if (lines > 120) {
        ++longOnes;
        MESSAGE(file.filename().string() << ":" << first << ": a function of " << lines << " lines");
      }
    }
  CHECK(functions > 100);  // (the scanner finds the functions at all)
  CHECK(longOnes == 0);
}

TEST_CASE("structure: the function-length scanner finds a long function and skips classes" * doctest::test_suite("cpu")) {
  montecl_test::TempDir dir;
  std::string body;
  for (int i = 0; i < 130; ++i) body += "  x += " + std::to_string(i) + ";  // { not a brace \"}\"\n";
  dir.write("f.cpp", "namespace a {\nstruct S {\n  int f() {\n    return 1;\n  }\n};\nint g(int x) {\n" + body +
                         "  return x;\n}\n}  // namespace a\n");
  const auto lengths = functionLengths(dir.file("f.cpp"));
  REQUIRE(lengths.size() == 2);
  CHECK(lengths[0].second == 3);    // S::f
  CHECK(lengths[1].second == 133);  // g: its head line, 130 lines, return, closing brace
}

TEST_CASE("structure: every stage of the stage table runs in some conformance case" * doctest::test_suite("cpu")) {
  std::vector<std::string> skipped;
  montecl::ConformanceSetOptions setOptions;
  setOptions.size = 4;
  setOptions.spp = 1;
  setOptions.cornellPath = "/nonexistent/scene.json";  // the analytic scenes alone cover every stage
  const std::vector<montecl::ConformanceCase> cases = montecl::conformanceSet(setOptions, skipped);
  std::set<std::string> launched;
  for (const montecl::ConformanceCase& c : cases) {
    montecl::RenderOptions o;
    o.profile = true;
    o.aovs = c.aovs;
    montecl::WavefrontRenderer host(montecl::hostDeviceInfo(), o);
    montecl::RenderStats stats;
    montecl::RenderPart part;
    part.textures = c.textures.get();
    const montecl::Bvh bvh = montecl::buildBvh(c.scene.triangles);
    host.render(c.scene, bvh, stats, {}, part);
    for (const montecl::StageTime& t : stats.profile.stages) launched.insert(t.name.substr(0, t.name.find(' ')));
  }
  for (int s = 0; s < montecl::kStageCount; ++s) {
    const std::string name = montecl::stageName(montecl::Stage(s));
    // The fused stages run only the stage bodies, and only on OpenCL devices with packet stages
    // (the host backend launches stage by stage): test_fused_waves.cpp runs each of them.
    if (montecl::stageIsFused(montecl::Stage(s))) continue;
    CHECK_MESSAGE(launched.count(name), "stage " << name << " runs in no conformance case (host/conformance/scenes.cpp)");
  }
}

}  // namespace test_file_structure
