// test_conformance.cpp: portability. The host backend (--device host) renders the same images as
// the kernels: in process against the default OpenCL device, and through the real montecl
// binary's `conformance` command on the PoCL pthread device, the PoCL single-threaded device
// (POCL_DEVICES=basic) and under Oclgrind (API, data-race and uninitialised-value checks, which must
// report nothing). Same-seed images agree within 1e-5 relative per pixel everywhere.
#include <doctest/doctest.h>

#include <cstdlib>
#include <regex>
#include <sstream>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cl/kernel_source.h"
#include "cli_runner.h"
#include "conformance/conformance.h"
#include "render/wavefront.h"
#include "test_scenes.h"

using namespace montecl;
using namespace montecl_test;

namespace {

Film render(const DeviceInfo& device, const Scene& scene, RenderOptions options = {}) {
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, options);
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

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
    }
  }
}

}  // namespace

TEST_CASE("host backend: selected by --device host, needs no OpenCL context") {
  DeviceInfo host = selectDevice("host");
  REQUIRE(host.isHost);
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 8, 4);
  s.render.aoSampling = montecl::AoSampling::Cosine;
  Film f = render(host, s);
  for (std::size_t p = 0; p < f.sum.size(); ++p) {
    REQUIRE(f.sum[p].w == 4.0f);
    REQUIRE(f.sum[p].x == 4.0f);
  }
}

TEST_CASE("host backend: bit-identical across wave sizes (one thread or several)") {
  const DeviceInfo host = hostDeviceInfo();
  Scene s = wallScene(48, 4);  // 9216 items: the default wave runs on several threads
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.seed = 3;
  Film reference = render(host, s);
  for (std::uint64_t wave : {1000ull, 4096ull + 17}) {
    RenderOptions o;
    o.waveSize = wave;
    CAPTURE(wave);
    Film f = render(host, s, o);
    CHECK(f.sum == reference.sum);
    CHECK(f.sumSq == reference.sumSq);
  }
}

TEST_CASE("host backend agrees with the default OpenCL device on the conformance set") {
  ConformanceOptions o;
  o.deviceSpecs = {""};
  o.set.size = 8;
  o.set.spp = 4;
  o.set.cornellSize = 16;
  o.set.cornellSpp = 2;
  o.set.cornellPath = std::string(MONTECL_SHARED_SCENES) + "/cornell-box/scene.json";
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

TEST_CASE("conformance: PoCL pthread device (montecl conformance --json)") {
  checkConformanceRun(runMontecl({"conformance", "--json", "--size", "12", "--spp", "4", "--cornell-size", "16",
                                  "--cornell-spp", "2"}),
                      "default platform");
}

TEST_CASE("conformance: PoCL single-threaded device (POCL_DEVICES=basic)") {
  CliResult r = runMontecl({"devices", "--json"}, {"POCL_DEVICES=basic"});
  REQUIRE(r.exitCode == 0);
  bool basic = false;
  for (const auto& d : nlohmann::json::parse(r.out))
    if (d["name"].get<std::string>().find("basic") != std::string::npos) basic = true;
  if (!basic) {
    MESSAGE("skipping: POCL_DEVICES=basic gives no 'basic' device (not PoCL?)\n" << r.out);
    return;
  }
  checkConformanceRun(runMontecl({"conformance", "--json", "--size", "12", "--spp", "4", "--cornell-size", "16",
                                  "--cornell-spp", "2"},
                                 {"POCL_DEVICES=basic"}),
                      "POCL_DEVICES=basic");
}

// scripts/oclgrind_check.sh: --check-api --data-races --uninitialized, kernels built with
// -cl-opt-disable (see the script); it fails on any Oclgrind report.
TEST_CASE("conformance: Oclgrind reports no API error, data race or uninitialised value") {
  if (std::system("oclgrind --version > /dev/null 2>&1") != 0) {
    MESSAGE("skipping: oclgrind not installed (apt-get install oclgrind)");
    return;
  }
  CliResult r = runProgram({"bash", std::string(MONTECL_SOURCE_DIR) + "/scripts/oclgrind_check.sh", MONTECL_EXE, "--json"});
  checkConformanceRun(r, "oclgrind");
  // Oclgrind reports every error on stderr; montecl writes nothing there with --json.
  CHECK(r.err.empty());
  nlohmann::json j = nlohmann::json::parse(r.out);
  REQUIRE(j["devices"].size() == 1);
  CHECK(j["devices"][0]["platform"].get<std::string>().find("Oclgrind") != std::string::npos);
}

TEST_CASE("kernel hygiene: no doubles, no unsuffixed float literals, no FP contraction") {
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
