// test_conformance.cpp: portability. The host backend renders the same images as the kernels: in
// process against the default OpenCL device, and through the real montecl binary's `conformance`
// command on the PoCL pthread device, the PoCL single-threaded device (POCL_DEVICES=basic), Intel's
// CPU OpenCL runtime (when scripts/setup.sh --intel-opencl installed it) and under Oclgrind (API,
// data-race and uninitialised-value checks, which must report nothing). Same-seed images are
// bit-identical everywhere (`pass` requires it; differingBits must be 0). Also the kernels' float hygiene.
#include <doctest/doctest.h>

#include <cstdlib>
#include <regex>
#include <sstream>
#include <nlohmann/json.hpp>

#include "cl/devices.h"
#include "cl/kernel_source.h"
#include "cli_runner.h"
#include "conformance/conformance.h"
#include "skip.h"

namespace test_file_conformance {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// Checks a `montecl conformance --json` run: exit 0, at least one device, every image rendered
// and within the tolerance.
void checkConformanceRun(const CliResult& r, const char* what) {
  INFO(what << ": exit " << r.exitCode << "\nstdout:\n" << r.out << "\nstderr:\n" << r.err);
  REQUIRE(r.exitCode == 0);
  nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["pass"] == true);
  REQUIRE(j["devices"].size() >= 1);
  for (const auto& d : j["devices"]) {
    CHECK(d["build"]["ok"] == true);
    REQUIRE(d["images"].size() >= 7);
    for (const auto& img : d["images"]) {
      CAPTURE(img.dump());
      CHECK(img["rendered"] == true);
      CHECK(img["pass"] == true);
      CHECK(img["maxRelDiff"].get<double>() <= 1e-5);
      CHECK(img["differingBits"].get<std::uint64_t>() == 0u);
    }
  }
}

}  // namespace

TEST_CASE("host backend agrees with the default OpenCL device on the conformance set" * doctest::test_suite("opencl")) {
  ConformanceOptions o;
  o.deviceSpecs = {""};
  o.set.size = 8;
  o.set.spp = 4;
  o.set.cornellSize = 16;
  o.set.cornellSpp = 2;
  o.set.cornellPath = sharedScenes() + "/cornell-box/scene.json";
  ConformanceReport report = runConformance(o);
  INFO(conformanceTable(report));
  REQUIRE(report.devices.size() == 1);
  CHECK(report.devices[0].buildOk);
  for (const ImageComparison& c : report.devices[0].images) {
    CAPTURE(c.name);
    CHECK(c.pass);
    CHECK(c.maxRelDiff <= kRelTolerance);
  }
  CHECK(report.pass);
}

TEST_CASE("conformance: PoCL pthread device (montecl conformance --json)" * doctest::test_suite("cli")) {
  checkConformanceRun(runMontecl({"conformance", "--json", "--size", "12", "--spp", "4", "--cornell-size", "16",
                                  "--cornell-spp", "2"}),
                      "default platform");
}

TEST_CASE("conformance: PoCL single-threaded device (POCL_DEVICES=basic)" * doctest::test_suite("cli")) {
  CliResult r = runMontecl({"devices", "--json"}, {"POCL_DEVICES=basic"});
  REQUIRE(r.exitCode == 0);
  bool basic = false;
  for (const auto& d : nlohmann::json::parse(r.out))
    if (d["name"].get<std::string>().find("basic") != std::string::npos) basic = true;
  MCL_SKIP_UNLESS(basic, "POCL_DEVICES=basic gives no 'basic' device (not PoCL?): " << r.out);
  checkConformanceRun(runMontecl({"conformance", "--json", "--size", "12", "--spp", "4", "--cornell-size", "16",
                                  "--cornell-spp", "2"},
                                 {"POCL_DEVICES=basic"}),
                      "POCL_DEVICES=basic");
}

// Intel's CPU OpenCL runtime, a second OpenCL implementation with its own compiler (it packs work
// items into SIMD lanes): installed by `scripts/setup.sh --intel-opencl` (scripts/test.sh does),
// made visible beside PoCL by scripts/with_intel_opencl.sh, which exits 3 when it is not installed.
TEST_CASE("conformance: Intel's CPU OpenCL runtime (scripts/with_intel_opencl.sh)" * doctest::test_suite("cli")) {
  const std::string wrapper = std::string(MONTECL_SOURCE_DIR) + "/scripts/with_intel_opencl.sh";
  CliResult probe = runProgram({"bash", wrapper, "true"});
  MCL_SKIP_UNLESS(probe.exitCode != 3, "Intel's CPU OpenCL runtime is not installed (scripts/setup.sh --intel-opencl): "
                                           << probe.err);
  REQUIRE(probe.exitCode == 0);
  CliResult list = runProgram({"bash", wrapper, MONTECL_EXE, "devices", "--json"});
  INFO("devices: exit " << list.exitCode << "\n" << list.out << list.err);
  REQUIRE(list.exitCode == 0);
  std::string intel;
  bool pocl = false;
  for (const auto& d : nlohmann::json::parse(list.out)) {
    const std::string platform = d["platform"].get<std::string>();
    if (platform.find("Intel(R) OpenCL") != std::string::npos && d["type"] == "CPU") {
      intel = d["index"].get<std::string>();
      CHECK(d["tuning"]["buildOptions"].get<std::string>().find("-DMCL_SCALAR_WORK_ITEMS") != std::string::npos);
    }
    if (platform.find("Portable Computing Language") != std::string::npos) {
      pocl = true;
      // PoCL builds the kernels as written, with the prefetch hints of both CPU runtimes only.
      CHECK(d["tuning"]["buildOptions"] == "-DMCL_PREFETCH_HINTS=1");
    }
  }
  REQUIRE_MESSAGE(!intel.empty(), "the runtime is installed but no Intel(R) OpenCL CPU device is listed");
  CHECK_MESSAGE(pocl, "PoCL is no longer listed beside the Intel runtime");
  CliResult r = runProgram({"bash", wrapper, MONTECL_EXE, "conformance", "--json", "--device", intel, "--size", "12",
                            "--spp", "4", "--cornell-size", "16", "--cornell-spp", "2"});
  checkConformanceRun(r, "Intel CPU runtime");
  nlohmann::json j = nlohmann::json::parse(r.out);
  REQUIRE(j["devices"].size() == 1);
  CHECK(j["devices"][0]["platform"].get<std::string>().find("Intel(R) OpenCL") != std::string::npos);
}

// scripts/oclgrind_check.sh: --check-api --data-races --uninitialized, kernels built with
// -cl-opt-disable (see the script); it fails on any Oclgrind report.
TEST_CASE("conformance: Oclgrind reports no API error, data race or uninitialised value" * doctest::test_suite("cli slow uninstrumented")) {
  MCL_SKIP_UNLESS(std::system("oclgrind --version > /dev/null 2>&1") == 0,
                  "oclgrind not installed (apt-get install oclgrind)");
  CliResult r = runProgram({"bash", std::string(MONTECL_SOURCE_DIR) + "/scripts/oclgrind_check.sh", MONTECL_EXE, "--json"});
  checkConformanceRun(r, "oclgrind");
  // Oclgrind reports every error on stderr; montecl writes nothing there with --json.
  CHECK(r.err.empty());
  nlohmann::json j = nlohmann::json::parse(r.out);
  REQUIRE(j["devices"].size() == 1);
  CHECK(j["devices"][0]["platform"].get<std::string>().find("Oclgrind") != std::string::npos);
}

TEST_CASE("kernel hygiene: no doubles, no unsuffixed float literals, no FP contraction" * doctest::test_suite("cpu")) {
  for (const char* file : {"montecl.cl", "integrate.cl"}) {
    CAPTURE(file);
    const std::string source = expandedKernelSource(file);
    // OpenCL C part only: the C++ branches (#ifndef MCL_OPENCL, #else of #ifdef MCL_OPENCL) are skipped.
    struct Block {
      bool onMcl, cxx;
    };
    std::vector<Block> stack;
    std::istringstream lines(source);
    std::string line;
    const std::regex doubleWord(R"(\bdouble\b)"), literal(R"((^|[^\w.])(\d+\.\d*|\.\d+)([eE][-+]?\d+)?(?![\w]))");
    while (std::getline(lines, line)) {
      if (line.rfind("#ifdef MCL_OPENCL", 0) == 0) stack.push_back({true, false});
      else if (line.rfind("#ifndef MCL_OPENCL", 0) == 0) stack.push_back({true, true});
      else if (line.rfind("#if", 0) == 0) stack.push_back({false, false});
      else if (line.rfind("#else", 0) == 0 && !stack.empty() && stack.back().onMcl) stack.back().cxx = !stack.back().cxx;
      else if (line.rfind("#endif", 0) == 0 && !stack.empty()) stack.pop_back();
      bool cxx = false;
      for (const Block& blk : stack) cxx = cxx || blk.cxx;
      if (cxx) continue;
      const std::string code = line.substr(0, line.find("//"));
      CAPTURE(line);
      CHECK_FALSE(std::regex_search(code, doubleWord));
      CHECK_FALSE(std::regex_search(code, literal));
    }
    if (std::string(file) == "montecl.cl") CHECK(source.find("#pragma OPENCL FP_CONTRACT OFF") != std::string::npos);
  }
}

}  // namespace test_file_conformance
