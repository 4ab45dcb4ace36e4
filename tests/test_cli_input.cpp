// test_cli_input.cpp: command-line input rules of `montecl render` (host/cli/validators.h): every
// numeric option is checked before any work, with a short message (no 300-digit bounds), NaN and
// infinity are refused, and the image size and light samples follow the scene file's limits.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "cli_runner.h"
#include "sanitizers.h"
#include "skip.h"
#include "cl/devices.h"
#include "render/memory_check.h"
#include "scene/render_settings.h"
#include "util/errors.h"

namespace test_file_cli_input {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
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

TEST_CASE("cli: integer options out of range say 'must be a positive integer'" * doctest::test_suite("cli sanitize")) {
  for (const char* opt : {"--spp", "--width", "--height", "--light-samples", "--wave-size", "--work-group-size"})
    for (const char* value : {"0", "-3", "1.5", "nan"}) {
      std::string err = badOption(opt, value);
      CHECK_MESSAGE(err.find("must be a positive integer") != std::string::npos, opt << " " << value << ": " << err);
    }
}

TEST_CASE("cli: choice options take their names only, not the enum's numbers" * doctest::test_suite("cli sanitize")) {
  const std::string scene = MONTECL_SOURCE_DIR "/scenes/demo/scene.json";
  TempDir dir;
  for (const char* option : {"--integrator", "--ao-sampling", "--direct-sampling"})
    for (const char* value : {"0", "1", "Direct", "pathtrace"}) {
      CliResult r = runMontecl({"render", scene, option, value, "--width", "8", "--height", "8", "--spp", "1",
                                "-q", "-o", dir.file("x.png")});
      CAPTURE(option);
      CAPTURE(value);
      CHECK(r.exitCode == 2);
      CHECK(r.err.find(option) != std::string::npos);
    }
}

TEST_CASE("cli: float options refuse zero, NaN and infinity: 'must be a positive number'" * doctest::test_suite("cli sanitize")) {
  for (const char* opt : {"--ao-distance", "--target-error", "--time"})
    for (const char* value : {"0", "-1", "nan", "NaN", "inf", "-inf", "1e999"}) {
      std::string err = badOption(opt, value);
      CHECK_MESSAGE(err.find("must be a positive number") != std::string::npos, opt << " " << value << ": " << err);
    }
  // --ao-distance is a float: a double beyond the float range would become inf.
  CHECK(badOption("--ao-distance", "1e39").find("up to 3.40282e+38") != std::string::npos);
}

TEST_CASE("cli: --width/--height follow the scene file's 16384 cap; --light-samples its 1024 cap" * doctest::test_suite("cli sanitize")) {
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

TEST_CASE("cli: an mtllib that is a FIFO is refused at once, not opened (which would block)" * doctest::test_suite("cli sanitize")) {
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

TEST_CASE("cli: an image too large for memory is refused before allocating, saying how much it needs" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  // 8192x8192 needs several GiB; the machine is declared to have 1 GB. Without the check the
  // render starts (and --time stops it after one wave, exit 0).
  CliResult r = runMontecl({"render", kGoodScene, "-q", "--device", "host", "--spp", "1", "--time", "0.01",
                            "--width", "8192", "--height", "8192", "-o", dir.file("out.png")},
                           {"MONTECL_MEMORY_LIMIT=1000000000"});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("image 8192x8192: needs about") != std::string::npos);
  CHECK(r.err.find("GiB") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(!fs::exists(dir.file("out.png")));
}

TEST_CASE("cli: on a CPU OpenCL device the device buffers count against this machine's memory too" * doctest::test_suite("cli sanitize")) {
  MCL_SKIP_UNLESS(montecl::selectDevice("").isCpu, "the default OpenCL device is not a CPU");
  TempDir dir;
  // 4096x4096: the host's copies (film read back, output planes) take about 2.1 GB and the device's
  // film and wave buffers about 1.4 GB more, in this machine's memory on a CPU device; 2.5 GB
  // covers the first but not both. Without the device part the render starts (--time stops it).
  CliResult r = runMontecl({"render", kGoodScene, "-q", "--spp", "1", "--time", "0.01", "--width", "4096",
                            "--height", "4096", "-o", dir.file("out.png")},
                           {"MONTECL_MEMORY_LIMIT=2500000000"});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("image 4096x4096: needs about") != std::string::npos);
  CHECK(!fs::exists(dir.file("out.png")));
}

TEST_CASE("cli: running out of memory is one clear line and exit 1, never a bare std::bad_alloc" * doctest::test_suite("cli sanitize")) {
#if MCL_TEST_UNDER_ASAN
  // ASan reserves terabytes of shadow address space at start-up: under `ulimit -v` it cannot start.
  MCL_SKIP_UNLESS(false, "an address-space limit (ulimit -v) cannot run an AddressSanitizer build");
#endif
  TempDir dir;
  // Address space capped at 400 MB and the memory check told there is plenty: the allocation fails.
  const std::string cmd = "ulimit -v 400000; exec \"$0\" render \"$1\" -q --device host --spp 1 --width 8192 "
                          "--height 8192 -o \"$2\"";
  CliResult r = montecl_test::runProgram({"sh", "-c", cmd, MONTECL_EXE, kGoodScene, dir.file("out.png")},
                                         {"MONTECL_MEMORY_LIMIT=100000000000000"});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.err == "montecl: error: out of memory: the scene or image is too large for this machine\n");
}

TEST_CASE("memory check: an OpenCL device's global memory bounds the film; the host adds its copies" * doctest::test_suite("cpu")) {
  montecl::DeviceInfo dev;
  dev.name = "Small GPU";
  dev.globalMemBytes = 1ull << 30;
  const montecl::ImageMemory need = montecl::imageMemoryNeed(4096ull * 4096, false, 256ull << 20);
  // The film: mean, meanLo, m2, m2Lo (float4 each) and the active list's uint per pixel.
  CHECK(need.device == 4096ull * 4096 * (4 * 16 + 4) + (256ull << 20));
  CHECK(need.host > 4096ull * 4096 * (4 * 16 + 8));
  // The sobol sampler's sub-sequences: K float4 per pixel more on the device, and their planes on the host.
  const montecl::ImageMemory split = montecl::imageMemoryNeed(4096ull * 4096, false, 256ull << 20, 8);
  CHECK(split.device == need.device + 4096ull * 4096 * 8 * 16);
  CHECK(split.host >= need.host + 4096ull * 4096 * (8 * 16 + 2 * 4 * (4 * 8 + 3)));
  CHECK_NOTHROW(montecl::checkImageMemory(dev, "s.json", 1024, 1024, true, 256ull << 20));
  try {
    montecl::checkImageMemory(dev, "s.json", 8192, 4096, false, 256ull << 20);
    FAIL("no error for a film of 1.1 GiB on a 1 GiB device");
  } catch (const montecl::InputError& e) {
    CHECK(std::string(e.what()) == "s.json: image 8192x4096: needs about 2.4 GiB of device memory (film and output "
                                   "image), Small GPU has 1.0 GiB; use a smaller --width/--height");
  }
}

TEST_CASE("cli: direct render of emitters facing away from everything warns; two_sided_emission lights it" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  // Floor at y = 0; a light quad at y = 1 whose front face (counter-clockwise) looks up, away.
  dir.write("floor.obj", "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 4 3 2\n");
  dir.write("light.obj", "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\nf 1 4 3 2\n");
  const std::string cam = R"("camera": {"position": [0, 0.5, 4], "target": [0, 0, 0], "fov_y": 40, "width": 16, "height": 16})";
  const std::string render = R"("render": {"integrator": "direct", "spp": 4})";
  dir.write("away.json", "{" + cam + ", " + render + R"(, "meshes": [{"file": "floor.obj"}, {"file": "light.obj", "emission": [5, 5, 5]}]})");
  dir.write("two.json", "{" + cam + ", " + render +
                            R"(, "meshes": [{"file": "floor.obj"}, {"file": "light.obj", "emission": [5, 5, 5], "two_sided_emission": true}]})");
  CliResult away = runMontecl({"render", dir.file("away.json"), "-q", "-o", dir.file("away.png")});
  INFO("stderr: " << away.err);
  CHECK(away.exitCode == 0);
  CHECK(away.err.find("away.json: no emitter's front face faces any surface") != std::string::npos);
  CHECK(away.err.find("two_sided_emission") != std::string::npos);
  CliResult two = runMontecl({"render", dir.file("two.json"), "-q", "-o", dir.file("two.png")});
  INFO("stderr: " << two.err);
  CHECK(two.exitCode == 0);
  CHECK(two.err.empty());
}

namespace {

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("cli: the default output of a scene.json is named after its folder and never replaces a file" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  fs::create_directories(dir.file("cornell-box"));
  fs::create_directories(dir.file("work"));
  const std::string quad = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/quad.obj";
  dir.write("cornell-box/scene.json", R"({"camera": {"position": [0, 0, 2], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
    "meshes": [{"file": ")" + quad + R"("}], "render": {"spp": 1}})");
  const std::string scene = dir.file("cornell-box/scene.json"), work = dir.file("work");
  CliResult first = montecl_test::runMonteclIn(work, {"render", scene, "-q"});
  INFO("stderr: " << first.err << " stdout: " << first.out);
  REQUIRE(first.exitCode == 0);
  CHECK(first.out.rfind("wrote cornell-box.png: ", 0) == 0);
  CHECK(fs::exists(dir.file("work/cornell-box.png")));
  CHECK(!fs::exists(dir.file("work/scene.png")));

  dir.write("work/cornell-box.png", "keep me");
  CliResult second = montecl_test::runMonteclIn(work, {"render", scene, "-q"});
  INFO("second: " << second.err << " " << second.out);
  CHECK(second.exitCode == 0);
  CHECK(fileText(dir.file("work/cornell-box.png")) == "keep me");
  CHECK(fs::exists(dir.file("work/cornell-box-1.png")));
  CHECK(second.out.rfind("wrote cornell-box-1.png: ", 0) == 0);
  CHECK(second.out.find("cornell-box.png exists and was kept; --overwrite replaces it") != std::string::npos);
  CHECK(montecl_test::runMonteclIn(work, {"render", scene, "-q"}).out.rfind("wrote cornell-box-2.png: ", 0) == 0);

  CliResult over = montecl_test::runMonteclIn(work, {"render", scene, "-q", "--overwrite"});
  CHECK(over.exitCode == 0);
  CHECK(over.out.rfind("wrote cornell-box.png: ", 0) == 0);
  CHECK(fileText(dir.file("work/cornell-box.png")) != "keep me");
  // An explicit -o replaces as before.
  CHECK(montecl_test::runMonteclIn(work, {"render", scene, "-q", "-o", "cornell-box-1.png"}).out.rfind("wrote cornell-box-1.png: ", 0) == 0);
  CHECK(!fs::exists(dir.file("work/cornell-box-3.png")));
}

TEST_CASE("cli: -v prints the camera as scene JSON; pasted into a scene file it renders the same image" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string obj = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/quad.obj";
  // AO, the scene file's default integrator (a bare model's is path under a sky: test_cli_view_env).
  CliResult bare = runMontecl({"render", obj, "-v", "-q", "--width", "12", "--height", "10", "--spp", "2", "--device",
                               "host", "--integrator", "ao", "-o", dir.file("bare.pfm")});
  INFO("stderr: " << bare.err);
  REQUIRE(bare.exitCode == 0);
  const std::size_t at = bare.err.find("montecl: \"camera\": {");
  REQUIRE(at != std::string::npos);
  const std::string camera = bare.err.substr(at + 9, bare.err.find('\n', at) - at - 9);
  dir.write("scene.json", "{" + camera + R"(, "meshes": [{"file": ")" + obj + R"("}], "render": {"spp": 2}})");
  CliResult scene = runMontecl({"render", dir.file("scene.json"), "-q", "--device", "host", "-o", dir.file("scene.pfm")});
  INFO("scene stderr: " << scene.err << " camera: " << camera);
  REQUIRE(scene.exitCode == 0);
  CHECK(fileText(dir.file("bare.pfm")) == fileText(dir.file("scene.pfm")));
}


TEST_CASE("cli: settings --json is every setting's default, by key, as the table has it" * doctest::test_suite("cli sanitize")) {
  const CliResult r = runMontecl({"settings", "--json"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const montecl::RenderSettings defaults;
  CHECK(j.size() == montecl::renderSettings().size());
  for (const montecl::RenderSetting& s : montecl::renderSettings()) {
    CAPTURE(s.key);
    REQUIRE(j.contains(s.key));
    const std::string text = montecl::settingValueText(s.get(defaults));
    const nlohmann::json& v = j[s.key];
    if (v.is_string()) CHECK(v.get<std::string>() == text);
    if (v.is_boolean()) CHECK((v.get<bool>() ? "true" : "false") == text);
    if (v.is_number()) CHECK(v.get<double>() == doctest::Approx(std::stod(text)).epsilon(1e-6));
    if (v.is_array()) CHECK(v.size() == 3);
  }
  CHECK(j["spp"] == defaults.spp);
  CHECK(j["max_depth"] == defaults.maxDepth);
  CHECK(runMontecl({"settings", "--json", "--markdown"}).exitCode == 2);
}

}  // namespace test_file_cli_input
