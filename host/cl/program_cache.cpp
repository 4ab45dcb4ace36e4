// program_cache.cpp: builds OpenCL programs, keeping each built binary on disk keyed by a hash of
// everything that affects it (platform, device, driver, options, full source). A hit loads the
// binary and builds it; a stale or unusable binary silently falls back to a source build. The
// cache is best effort: a folder that cannot be created or written never fails a build.
#include "cl/program_cache.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

#include "cl/cache_entry.h"
#include "cl/cl_errors.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/hash.h"

namespace montecl {
namespace fs = std::filesystem;

namespace {

// The entry format (magic, key check, size, checksum, binary) is in cl/cache_entry.h.
constexpr std::uint64_t kCheckSeed = 0x84222325cbf29ce4ull;

std::string envOr(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

// Intel's CPU runtime reads compiler settings from CL_CONFIG_* variables (e.g.
// CL_CONFIG_CPU_VECTORIZER_MODE): "NAME=value\n" for each, sorted, so they key the cache too.
std::string clConfigEnvironment() {
  std::vector<std::string> vars;
  for (char** e = environ; e && *e; ++e)
    if (std::strncmp(*e, "CL_CONFIG_", 10) == 0) vars.emplace_back(*e);
  std::sort(vars.begin(), vars.end());
  std::string out;
  for (const std::string& v : vars) out += v + "\n";
  return out;
}

std::string buildLog(const cl::Program& program, cl_device_id dev) {
  size_t n = 0;
  if (clGetProgramBuildInfo(program(), dev, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n) != CL_SUCCESS ||
      n == 0)
    return "";
  std::string log(n, '\0');
  if (clGetProgramBuildInfo(program(), dev, CL_PROGRAM_BUILD_LOG, n, &log[0], nullptr) !=
      CL_SUCCESS)
    return "";
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n' || log.back() == ' '))
    log.pop_back();
  return log;
}

cl_int build(const cl::Program& program, cl_device_id dev, const std::string& options) {
  return clBuildProgram(program(), 1, &dev, options.c_str(), nullptr, nullptr);
}

// The binary of `program` for `dev`; empty if the driver does not provide one.
std::vector<unsigned char> programBinary(const cl::Program& program, cl_device_id dev) {
  std::vector<cl::Device> devices = program.getInfo<CL_PROGRAM_DEVICES>();
  std::vector<std::vector<unsigned char>> binaries = program.getInfo<CL_PROGRAM_BINARIES>();
  for (std::size_t i = 0; i < devices.size() && i < binaries.size(); ++i)
    if (devices[i]() == dev) return binaries[i];
  return {};
}

// Empty when path is absent or a regular file; else what it is (the cache is then skipped: a
// folder, a FIFO (which would block the read) or a device such as /dev/zero (endless)).
std::string notRegularFile(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st) || fs::is_regular_file(st)) return "";
  if (fs::is_directory(st)) return "a directory";
  if (fs::is_fifo(st)) return "a FIFO";
  return "not a regular file";
}

void writeCacheFile(const std::string& path, std::uint64_t check,
                    const std::vector<unsigned char>& bin) {
  const std::vector<unsigned char> entry = encodeCacheEntry(check, bin);
  writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(entry.data()), static_cast<std::streamsize>(entry.size()));
    f.close();
    if (!f) throw RuntimeError(tmp + ": write failed");
  });
}

// Program built from a cached binary, or a null program when that does not work.
cl::Program fromBinary(const cl::Context& context, cl_device_id dev,
                       const std::vector<unsigned char>& bin, const std::string& options) {
  const unsigned char* ptr = bin.data();
  size_t size = bin.size();
  cl_int binStatus = CL_SUCCESS, err = CL_SUCCESS;
  cl_program raw =
      clCreateProgramWithBinary(context(), 1, &dev, &size, &ptr, &binStatus, &err);
  if (err != CL_SUCCESS || binStatus != CL_SUCCESS || !raw) {
    if (raw) clReleaseProgram(raw);
    return cl::Program();
  }
  cl::Program program(raw);  // takes ownership
  if (build(program, dev, options) != CL_SUCCESS) return cl::Program();
  return program;
}

}  // namespace

std::string programCacheDir() {
  std::string dir = envOr("MONTECL_CACHE_DIR");
  if (!dir.empty()) return dir;
  dir = envOr("XDG_CACHE_HOME");
  if (!dir.empty()) return dir + "/montecl";
  dir = envOr("HOME");
  if (!dir.empty()) return dir + "/.cache/montecl";
  return "";
}

ProgramBuild buildProgramCached(const cl::Context& context, const DeviceInfo& device,
                                const std::string& source, const std::string& options) {
  const auto start = std::chrono::steady_clock::now();
  const cl_device_id dev = device.device();
  ProgramBuild result;
  auto finish = [&]() {
    result.buildMs = std::chrono::duration<double, std::milli>(
                         std::chrono::steady_clock::now() - start)
                         .count();
    return result;
  };

  // Key everything that can change the binary; query the device itself rather than trusting the
  // DeviceInfo fields, which a caller may have left empty.
  cl::Device clDevice = device.device;
  cl::Platform platform(clDevice.getInfo<CL_DEVICE_PLATFORM>(), true);
  const std::string deviceName = clDevice.getInfo<CL_DEVICE_NAME>();
  // Drivers that take extra build options from the environment change the binary too.
  const char* oclgrindOptions = std::getenv("OCLGRIND_BUILD_OPTIONS");
  std::string key;
  for (const std::string& part :
       {platform.getInfo<CL_PLATFORM_NAME>(), platform.getInfo<CL_PLATFORM_VERSION>(), deviceName,
        clDevice.getInfo<CL_DRIVER_VERSION>(), options, std::string(oclgrindOptions ? oclgrindOptions : ""),
        clConfigEnvironment(), source}) {
    key += part;
    key.push_back('\0');
  }
  const std::uint64_t check = fnv1a64(key, kCheckSeed);

  std::string cachePath;
  const std::string dir = programCacheDir();
  if (!dir.empty()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!ec && fs::is_directory(dir, ec)) cachePath = dir + "/" + hex64(fnv1a64(key)) + ".bin";
    const std::string what = cachePath.empty() ? std::string() : notRegularFile(cachePath);
    if (!what.empty()) {
      std::cerr << "montecl: warning: program cache " << cachePath << " is " << what
                << "; building the kernels without the cache\n";
      cachePath.clear();
    }
  }

  if (!cachePath.empty()) {
    std::vector<unsigned char> bin;
    if (readCacheEntryFile(cachePath, check, bin)) {
      cl::Program program = fromBinary(context, dev, bin, options);
      if (program() != nullptr) {
        result.program = program;
        result.fromCache = true;
        result.cachePath = cachePath;
        return finish();
      }
    }
  }

  cl::Program program(context, source);
  cl_int err = build(program, dev, options);
  if (err != CL_SUCCESS) {
    std::string log = buildLog(program, dev);
    std::string msg = "kernel build failed on " + (device.name.empty() ? deviceName : device.name) +
                      ": " + (options.empty() ? "(no options)" : options) + "\n";
    if (err != CL_BUILD_PROGRAM_FAILURE || log.empty())
      msg += "clBuildProgram returned " + std::string(clErrorName(err)) + " (" +
             std::to_string(err) + ")" + (log.empty() ? "" : "\n");
    msg += log;
    throw RuntimeError(msg);
  }
  result.program = program;

  if (!cachePath.empty()) {
    try {
      std::vector<unsigned char> bin = programBinary(program, dev);
      if (!bin.empty()) {
        writeCacheFile(cachePath, check, bin);
        result.cachePath = cachePath;
      }
    } catch (...) {
      // Best effort: an unwritable cache or a driver without binaries only costs a rebuild.
    }
  }
  return finish();
}

}  // namespace montecl
