// test_cl.cpp: the OpenCL layer (host/cl): device listing and --device selection, error names,
// kernel-source include expansion, the on-disk program cache (hit, miss, fallback, build errors),
// and the host/device struct layout probe.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "cl/cl_errors.h"
#include "cl/devices.h"
#include "cl/kernel_source.h"
#include "cl/program_cache.h"
#include "kernels/shared/types.h"
#include "util/errors.h"

namespace test_file_cl {  // keeps this file's helpers apart in a unity batch

namespace fs = std::filesystem;
using namespace montecl;

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {


// Sets (or unsets, with nullptr) an environment variable for the lifetime of the object.
struct ScopedEnv {
  std::string name;
  bool had = false;
  std::string old;
  ScopedEnv(const char* n, const char* value) : name(n) {
    if (const char* v = std::getenv(n)) {
      had = true;
      old = v;
    }
    if (value)
      ::setenv(n, value, 1);
    else
      ::unsetenv(n);
  }
  ~ScopedEnv() {
    if (had)
      ::setenv(name.c_str(), old.c_str(), 1);
    else
      ::unsetenv(name.c_str());
  }
};


std::size_t count(const std::string& hay, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = hay.find(needle); pos != std::string::npos; pos = hay.find(needle, pos + 1)) ++n;
  return n;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

template <typename F>
std::string thrownMessage(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

const char* kDoubleKernel = R"(
__kernel void twice(__global uint* out) {
  uint i = get_global_id(0);
  out[i] = i * 2u;
}
)";

}  // namespace

// --- devices ------------------------------------------------------------------------------------

TEST_CASE("cl: listDevices finds a usable device" * doctest::test_suite("opencl sanitize")) {
  DeviceList list = listDevices();
  for (const auto& e : list.platformErrors) MESSAGE("platform error: " << e);
  REQUIRE(!list.devices.empty());
  for (const DeviceInfo& d : list.devices) {
    CHECK(!d.name.empty());
    CHECK(!d.platformName.empty());
    CHECK(d.computeUnits > 0);
    CHECK(d.globalMemBytes > 0);
    CHECK(d.maxAllocBytes > 0);
    CHECK(!d.typeName.empty());
    CHECK(d.device() != nullptr);
  }
}

TEST_CASE("cl: selectDevice by default, index, and name" * doctest::test_suite("opencl sanitize")) {
  DeviceInfo def = selectDevice("");
  CHECK(!def.name.empty());

  DeviceInfo first = selectDevice("0:0");
  CHECK(first.platformIndex == 0);
  CHECK(first.deviceIndex == 0);
  CHECK(deviceIndexString(first) == "0:0");

  DeviceList list = listDevices();
  REQUIRE(!list.devices.empty());
  const DeviceInfo& last = list.devices.back();
  std::string name = lower(last.name);
  std::string sub = name.substr(name.size() / 4, std::max<std::size_t>(1, name.size() / 2));
  DeviceInfo byName = selectDevice(sub);
  CHECK(lower(byName.name).find(sub) != std::string::npos);

  // Upper-cased platform name also matches (case-insensitive).
  std::string plat = last.platformName;
  for (char& c : plat) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  DeviceInfo byPlatform = selectDevice(plat);
  CHECK((lower(byPlatform.name).find(lower(plat)) != std::string::npos ||
         lower(byPlatform.platformName).find(lower(plat)) != std::string::npos));
}

TEST_CASE("cl: selectDevice rejects specs that match nothing" * doctest::test_suite("opencl sanitize")) {
  CHECK_THROWS_AS(selectDevice("nonexistent-xyz"), InputError);
  CHECK(thrownMessage([] { selectDevice("nonexistent-xyz"); }) ==
        "--device: no OpenCL device matches \"nonexistent-xyz\" (run 'montecl devices' to list "
        "them)");
  CHECK_THROWS_AS(selectDevice("9:9"), InputError);
}

TEST_CASE("cl: selectDevice(\"host\") is the host backend, whatever the case" * doctest::test_suite("opencl sanitize")) {
  for (const char* spec : {"host", "Host", " HOST "}) {
    DeviceInfo d = selectDevice(spec);
    CHECK(d.isHost);
    CHECK(deviceIndexString(d) == "host");
  }
  CHECK_FALSE(selectDevice("").isHost);
}

TEST_CASE("cl: formatBytes" * doctest::test_suite("cpu")) {
  CHECK(formatBytes(512) == "512 B");
  CHECK(formatBytes(1536) == "1.5 KiB");
  CHECK(formatBytes(1073741824ull) == "1.0 GiB");
  CHECK(formatBytes(3865470566ull) == "3.6 GiB");
}

// --- error names --------------------------------------------------------------------------------

TEST_CASE("cl: error names" * doctest::test_suite("cpu")) {
  CHECK(std::string(clErrorName(0)) == "CL_SUCCESS");
  CHECK(std::string(clErrorName(-5)) == "CL_OUT_OF_RESOURCES");
  CHECK(std::string(clErrorName(-11)) == "CL_BUILD_PROGRAM_FAILURE");
  CHECK(std::string(clErrorName(-54)) == "CL_INVALID_WORK_GROUP_SIZE");
  CHECK(std::string(clErrorName(-72)) == "CL_MAX_SIZE_RESTRICTION_EXCEEDED");
  CHECK(std::string(clErrorName(-1001)) == "CL_PLATFORM_NOT_FOUND_KHR");
  CHECK(std::string(clErrorName(-12345)) == "CL_ERROR(-12345)");
  CHECK(describeClError(cl::Error(-5, "clEnqueueNDRangeKernel")) ==
        "OpenCL call clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5)");
}

// --- kernel sources -----------------------------------------------------------------------------

TEST_CASE("cl: kernelFile reads the embedded copy, or MONTECL_KERNEL_DIR" * doctest::test_suite("cpu")) {
  {
    ScopedEnv env("MONTECL_KERNEL_DIR", nullptr);
    CHECK(kernelFile("shared/types.h").find("BvhNode") != std::string::npos);
    CHECK_THROWS_AS(kernelFile("no/such/file.cl"), RuntimeError);
  }
  TempDir dir;
  dir.write("k.cl", "hello kernel\n");
  ScopedEnv env("MONTECL_KERNEL_DIR", dir.path.c_str());
  CHECK(kernelFile("k.cl") == "hello kernel\n");
  std::string msg = thrownMessage([] { kernelFile("missing.cl"); });
  CHECK(msg.find(dir.path + "/missing.cl") != std::string::npos);
}

TEST_CASE("cl: expandedKernelSource expands includes once, relative to the including file" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("main.cl",
            "#include \"shared/a.h\"\n"
            "#include \"shared/b.h\"\n"
            "MAIN_MARK\n");
  dir.write("shared/a.h",
            "#pragma once\n"
            "#include \"b.h\"\n"
            "A_MARK\n");
  dir.write("shared/b.h",
            "#pragma once\n"
            "  #  include \"../common/c.h\"\n"
            "B_MARK\n");
  dir.write("common/c.h", "#pragma once\nC_MARK\n");
  dir.write("bad.cl", "#include \"shared/a.h\"\n#include \"shared/missing.h\"\n");
  ScopedEnv env("MONTECL_KERNEL_DIR", dir.path.c_str());

  std::string src = expandedKernelSource("main.cl");
  for (const char* mark : {"MAIN_MARK", "A_MARK", "B_MARK", "C_MARK"}) {
    CAPTURE(mark);
    CHECK(count(src, mark) == 1);
  }
  CHECK(src.find("C_MARK") < src.find("B_MARK"));
  CHECK(src.find("B_MARK") < src.find("A_MARK"));
  CHECK(src.find("A_MARK") < src.find("MAIN_MARK"));
  CHECK(src.find("#include") == std::string::npos);
  CHECK(src.find("pragma once") == std::string::npos);
  CHECK(src.find("#line 1 \"common/c.h\"") != std::string::npos);
  CHECK(src.find("#line 3 \"main.cl\"\nMAIN_MARK") != std::string::npos);

  std::string msg = thrownMessage([] { expandedKernelSource("bad.cl"); });
  CHECK(msg.find("shared/missing.h") != std::string::npos);
  CHECK(msg.find("bad.cl:2") != std::string::npos);
  CHECK_THROWS_AS(expandedKernelSource("bad.cl"), RuntimeError);
}

// --- program cache ------------------------------------------------------------------------------

TEST_CASE("cl: program cache hits, misses, falls back, and runs the cached program" * doctest::test_suite("opencl sanitize")) {
  TempDir dir;
  ScopedEnv env("MONTECL_CACHE_DIR", (dir.path + "/cache").c_str());
  CHECK(programCacheDir() == dir.path + "/cache");
  DeviceInfo dev = selectDevice("");
  cl::Context context(dev.device);
  const std::string opts = "-cl-std=CL1.2";

  ProgramBuild first = buildProgramCached(context, dev, kDoubleKernel, opts);
  CHECK_FALSE(first.fromCache);
  REQUIRE(!first.cachePath.empty());
  CHECK(fs::exists(first.cachePath));
  CHECK(fs::path(first.cachePath).parent_path() == fs::path(dir.path + "/cache"));

  ProgramBuild second = buildProgramCached(context, dev, kDoubleKernel, opts);
  CHECK(second.fromCache);
  CHECK(second.cachePath == first.cachePath);
  MESSAGE("source build " << first.buildMs << " ms, cached build " << second.buildMs << " ms");

  ProgramBuild other = buildProgramCached(context, dev, kDoubleKernel, opts + " -DUNUSED=1");
  CHECK_FALSE(other.fromCache);
  CHECK(other.cachePath != first.cachePath);

  // The program built from the cached binary actually runs.
  const std::size_t n = 64;
  cl::CommandQueue queue(context, dev.device);
  cl::Buffer buf(context, CL_MEM_WRITE_ONLY, n * sizeof(cl_uint));
  cl::Kernel kernel(second.program, "twice");
  kernel.setArg(0, buf);
  queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n));
  std::vector<cl_uint> out(n, 12345u);
  queue.enqueueReadBuffer(buf, CL_TRUE, 0, n * sizeof(cl_uint), out.data());
  for (std::size_t i = 0; i < n; ++i) CHECK(out[i] == 2 * i);

  // A cache file whose binary is garbage is ignored: rebuilt from source and rewritten.
  std::string bytes = readAll(first.cachePath);
  REQUIRE(bytes.size() > 16);
  std::ofstream(first.cachePath, std::ios::binary | std::ios::trunc)
      << bytes.substr(0, 16) << std::string(256, '\x5a');
  ProgramBuild fallback = buildProgramCached(context, dev, kDoubleKernel, opts);
  CHECK_FALSE(fallback.fromCache);
  CHECK(readAll(first.cachePath).find(std::string(256, '\x5a')) == std::string::npos);  // rewritten
  CHECK(buildProgramCached(context, dev, kDoubleKernel, opts).fromCache);

  // A file that is not a cache file at all is a miss too.
  std::ofstream(first.cachePath, std::ios::binary | std::ios::trunc) << "junk";
  CHECK_FALSE(buildProgramCached(context, dev, kDoubleKernel, opts).fromCache);
}

TEST_CASE("cl: program cache never fails a build when the folder is unusable" * doctest::test_suite("opencl sanitize")) {
  TempDir dir;
  dir.write("not-a-folder", "x");
  ScopedEnv env("MONTECL_CACHE_DIR", (dir.path + "/not-a-folder/cache").c_str());
  DeviceInfo dev = selectDevice("");
  cl::Context context(dev.device);
  ProgramBuild b = buildProgramCached(context, dev, kDoubleKernel, "-cl-std=CL1.2");
  CHECK_FALSE(b.fromCache);
  CHECK(b.cachePath.empty());
  CHECK(b.program() != nullptr);
}

TEST_CASE("cl: a kernel build error carries the build log" * doctest::test_suite("opencl sanitize")) {
  TempDir dir;
  ScopedEnv env("MONTECL_CACHE_DIR", dir.path.c_str());
  DeviceInfo dev = selectDevice("");
  cl::Context context(dev.device);
  const char* bad = "__kernel void k(__global uint* o) { o[0] = undeclared_thing_xyz; }\n";
  std::string msg;
  CHECK_THROWS_AS(buildProgramCached(context, dev, bad, "-cl-std=CL1.2"), RuntimeError);
  msg = thrownMessage([&] { buildProgramCached(context, dev, bad, "-cl-std=CL1.2"); });
  CHECK(msg.rfind("kernel build failed on " + dev.name + ": -cl-std=CL1.2\n", 0) == 0);
  CHECK(msg.find("undeclared_thing_xyz") != std::string::npos);
  CHECK(dir.entries().empty());  // nothing cached for a failed build

  // With expanded sources the log names the original file, thanks to the #line directives.
  TempDir kernels;
  kernels.write("main.cl", "#include \"shared/oops.h\"\n__kernel void k() {}\n");
  kernels.write("shared/oops.h", "#pragma once\n\nint f() { return missing_in_header_abc; }\n");
  ScopedEnv kenv("MONTECL_KERNEL_DIR", kernels.path.c_str());
  std::string src = expandedKernelSource("main.cl");
  msg = thrownMessage([&] { buildProgramCached(context, dev, src, "-cl-std=CL1.2"); });
  CHECK(msg.find("missing_in_header_abc") != std::string::npos);
  INFO(msg);
  // PoCL honours #line in its diagnostics; Oclgrind reports spelling locations ("input.cl:5").
  if (dev.platformName.find("Portable Computing Language") != std::string::npos) {
    CHECK(msg.find("shared/oops.h:3") != std::string::npos);
  } else {
    WARN(msg.find("shared/oops.h:3") != std::string::npos);
  }
}

// --- struct layout ------------------------------------------------------------------------------

TEST_CASE("cl: shared struct layout matches between host and device" * doctest::test_suite("opencl sanitize")) {
  TempDir dir;
  ScopedEnv cache("MONTECL_CACHE_DIR", dir.path.c_str());
  ScopedEnv kdir("MONTECL_KERNEL_DIR", nullptr);  // the embedded (real) headers
  std::string src = expandedKernelSource("shared/types.h") + R"(
#define OFF(T, f) ((uint)__builtin_offsetof(T, f))
__kernel void probe(__global uint* out) {
  out[0] = sizeof(BvhNode);
  out[1] = sizeof(Triangle);
  out[2] = sizeof(Material);
  out[3] = sizeof(Ray);
  out[4] = sizeof(Hit);
  out[5] = sizeof(ShadowWork);
  out[6] = sizeof(FrameParams);
  out[7] = OFF(BvhNode, maxX);
  out[8] = OFF(BvhNode, triCount);
  out[9] = OFF(Triangle, e2);
  out[10] = OFF(Material, emission);
  out[11] = OFF(Ray, dir);
  out[12] = OFF(Hit, tri);
  out[13] = OFF(Hit, v);
  out[14] = OFF(ShadowWork, ray);
  out[15] = OFF(FrameParams, camDx);
  out[16] = OFF(FrameParams, background);
  out[17] = OFF(FrameParams, width);
  out[18] = sizeof(WideNode);
  out[19] = OFF(WideNode, child);
  out[20] = sizeof(TriangleShading);
  out[21] = OFF(TriangleShading, tv);
  out[22] = OFF(FrameParams, sampler);
}
)";
  const std::vector<std::pair<const char*, cl_uint>> host = {
      {"sizeof(BvhNode)", sizeof(BvhNode)},
      {"sizeof(Triangle)", sizeof(Triangle)},
      {"sizeof(Material)", sizeof(Material)},
      {"sizeof(Ray)", sizeof(Ray)},
      {"sizeof(Hit)", sizeof(Hit)},
      {"sizeof(ShadowWork)", sizeof(ShadowWork)},
      {"sizeof(FrameParams)", sizeof(FrameParams)},
      {"offsetof(BvhNode, maxX)", offsetof(BvhNode, maxX)},
      {"offsetof(BvhNode, triCount)", offsetof(BvhNode, triCount)},
      {"offsetof(Triangle, e2)", offsetof(Triangle, e2)},
      {"offsetof(Material, emission)", offsetof(Material, emission)},
      {"offsetof(Ray, dir)", offsetof(Ray, dir)},
      {"offsetof(Hit, tri)", offsetof(Hit, tri)},
      {"offsetof(Hit, v)", offsetof(Hit, v)},
      {"offsetof(ShadowWork, ray)", offsetof(ShadowWork, ray)},
      {"offsetof(FrameParams, camDx)", offsetof(FrameParams, camDx)},
      {"offsetof(FrameParams, background)", offsetof(FrameParams, background)},
      {"offsetof(FrameParams, width)", offsetof(FrameParams, width)},
      {"sizeof(WideNode)", sizeof(WideNode)},
      {"offsetof(WideNode, child)", offsetof(WideNode, child)},
      {"sizeof(TriangleShading)", sizeof(TriangleShading)},
      {"offsetof(TriangleShading, tv)", offsetof(TriangleShading, tv)},
      {"offsetof(FrameParams, sampler)", offsetof(FrameParams, sampler)},
  };
  DeviceInfo dev = selectDevice("");
  cl::Context context(dev.device);
  ProgramBuild build = buildProgramCached(context, dev, src, "-cl-std=CL1.2");
  cl::CommandQueue queue(context, dev.device);
  cl::Buffer buf(context, CL_MEM_WRITE_ONLY, host.size() * sizeof(cl_uint));
  cl::Kernel kernel(build.program, "probe");
  kernel.setArg(0, buf);
  queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(1));
  std::vector<cl_uint> device(host.size(), 0xdeadbeefu);
  queue.enqueueReadBuffer(buf, CL_TRUE, 0, device.size() * sizeof(cl_uint), device.data());
  for (std::size_t i = 0; i < host.size(); ++i) {
    CAPTURE(host[i].first);
    CHECK(device[i] == host[i].second);
  }
}

}  // namespace test_file_cl
