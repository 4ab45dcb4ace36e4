// devices.cpp: enumerates OpenCL platforms and devices (a failing platform is recorded, not fatal)
// and picks the device a --device SPEC names: "P:D", a name substring, "" for the best default,
// or "host" for the host backend (the stage functions as C++ on the CPU, no OpenCL needed).
#include "cl/devices.h"

#include <algorithm>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <thread>

#include "cl/cl_errors.h"
#include "util/errors.h"

namespace montecl {

namespace {

constexpr cl_int kPlatformNotFoundKhr = -1001;

std::string trim(std::string s) {
  auto notSpace = [](unsigned char c) { return !std::isspace(c) && c != '\0'; };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), notSpace));
  s.erase(std::find_if(s.rbegin(), s.rend(), notSpace).base(), s.end());
  return s;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string typeNameOf(cl_device_type t) {
  std::string s;
  auto add = [&](cl_device_type bit, const char* name) {
    if (t & bit) s += (s.empty() ? "" : "+") + std::string(name);
  };
  add(CL_DEVICE_TYPE_GPU, "GPU");
  add(CL_DEVICE_TYPE_CPU, "CPU");
  add(CL_DEVICE_TYPE_ACCELERATOR, "accelerator");
  add(CL_DEVICE_TYPE_CUSTOM, "custom");
  return s.empty() ? "other" : s;
}

DeviceInfo describeDevice(const cl::Device& dev) {
  DeviceInfo d;
  d.device = dev;
  d.name = trim(dev.getInfo<CL_DEVICE_NAME>());
  d.vendor = trim(dev.getInfo<CL_DEVICE_VENDOR>());
  d.version = trim(dev.getInfo<CL_DEVICE_VERSION>());
  d.driverVersion = trim(dev.getInfo<CL_DRIVER_VERSION>());
  d.openclCVersion = trim(dev.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
  cl_device_type t = dev.getInfo<CL_DEVICE_TYPE>();
  d.isGpu = (t & CL_DEVICE_TYPE_GPU) != 0;
  d.isCpu = (t & CL_DEVICE_TYPE_CPU) != 0;
  d.typeName = typeNameOf(t);
  d.computeUnits = dev.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  d.globalMemBytes = dev.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  d.maxAllocBytes = dev.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  d.maxWorkGroupSize = dev.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  return d;
}

[[noreturn]] void throwNoMatch(const std::string& spec) {
  throw InputError("--device: no OpenCL device matches \"" + spec +
                   "\" (run 'montecl devices' to list them)");
}

}  // namespace

bool isOclgrind(const DeviceInfo& d) { return !d.isHost && d.platformName.find("Oclgrind") != std::string::npos; }

DeviceInfo hostDeviceInfo() {
  DeviceInfo d;
  d.isHost = true;
  d.platformIndex = d.deviceIndex = -1;
  d.name = "host backend (C++ stages on the CPU)";
  d.platformName = "montecl host";
  d.vendor = "montecl";
  d.typeName = "host";
  d.version = "none (no OpenCL)";
  d.isCpu = true;
  d.computeUnits = std::thread::hardware_concurrency();
  return d;
}

std::string deviceIndexString(const DeviceInfo& d) {
  if (d.isHost) return "host";
  return std::to_string(d.platformIndex) + ":" + std::to_string(d.deviceIndex);
}

std::string formatBytes(std::uint64_t bytes) {
  static const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB"};
  if (bytes < 1024) return std::to_string(bytes) + " B";
  double v = static_cast<double>(bytes);
  int u = -1;
  while (v >= 1024.0 && u < 4) {
    v /= 1024.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %s", v, units[u]);
  return buf;
}

// PoCL keeps its own kernel cache under $POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else
// ~/.cache/pocl, and when it cannot create it reports no devices at all ("no OpenCL device
// found"). Before the first OpenCL call: if that folder cannot be created and written, point
// POCL_CACHE_DIR at a fresh folder under the temporary directory and say so once.
static void ensureWritablePoclCache() {
  static bool done = false;
  if (done) return;
  done = true;
  namespace fs = std::filesystem;
  std::string dir;
  if (const char* v = std::getenv("POCL_CACHE_DIR"); v && *v) dir = v;
  else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) dir = std::string(x) + "/pocl";
  else if (const char* h = std::getenv("HOME"); h && *h) dir = std::string(h) + "/.cache/pocl";
  if (dir.empty()) return;
  std::error_code ec;
  fs::create_directories(dir, ec);
  bool writable = !ec && fs::is_directory(dir, ec);
  if (writable) {
    const std::string probe = dir + "/.montecl-probe-" + std::to_string(::getpid());
    std::FILE* f = std::fopen(probe.c_str(), "w");
    writable = f != nullptr;
    if (f) std::fclose(f);
    std::remove(probe.c_str());
  }
  if (writable) return;
  std::string tmpl = (fs::temp_directory_path(ec).string().empty() ? std::string("/tmp") : fs::temp_directory_path(ec).string()) +
                     "/montecl-pocl-XXXXXX";
  if (::mkdtemp(&tmpl[0]) == nullptr) {
    std::fprintf(stderr, "montecl: warning: %s is not a writable folder and no temporary folder could be made: "
                 "PoCL may find no devices; set POCL_CACHE_DIR to a writable folder\n", dir.c_str());
    return;
  }
  ::setenv("POCL_CACHE_DIR", tmpl.c_str(), 1);
  std::fprintf(stderr, "montecl: warning: %s is not a writable folder; PoCL's kernel cache is in %s for this run\n",
               dir.c_str(), tmpl.c_str());
}

DeviceList listDevices() {
  DeviceList list;
  std::vector<cl::Platform> platforms;
  ensureWritablePoclCache();
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    // The ICD loader reports "no platform" as an error; that simply means no devices.
    if (e.err() != kPlatformNotFoundKhr && e.err() != CL_DEVICE_NOT_FOUND)
      list.platformErrors.push_back(describeClError(e));
    return list;
  }
  for (std::size_t p = 0; p < platforms.size(); ++p) {
    std::string platformName, platformVersion;
    try {
      platformName = trim(platforms[p].getInfo<CL_PLATFORM_NAME>());
      platformVersion = trim(platforms[p].getInfo<CL_PLATFORM_VERSION>());
      std::vector<cl::Device> devices;
      try {
        platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
      } catch (const cl::Error& e) {
        if (e.err() != CL_DEVICE_NOT_FOUND) throw;
        continue;  // a platform without devices is not an error
      }
      for (std::size_t i = 0; i < devices.size(); ++i) {
        try {
          DeviceInfo d = describeDevice(devices[i]);
          d.platformIndex = static_cast<int>(p);
          d.deviceIndex = static_cast<int>(i);
          d.platformName = platformName;
          d.platformVersion = platformVersion;
          list.devices.push_back(std::move(d));
        } catch (const cl::Error& e) {
          list.platformErrors.push_back("platform " + std::to_string(p) + " (" + platformName +
                                        "), device " + std::to_string(i) + ": " +
                                        describeClError(e));
        }
      }
    } catch (const cl::Error& e) {
      std::string where = "platform " + std::to_string(p);
      if (!platformName.empty()) where += " (" + platformName + ")";
      list.platformErrors.push_back(where + ": " + describeClError(e));
    } catch (const std::exception& e) {
      list.platformErrors.push_back("platform " + std::to_string(p) + ": " + e.what());
    }
  }
  return list;
}

DeviceInfo selectDevice(const std::string& rawSpec) {
  const std::string spec = trim(rawSpec);
  if (lower(spec) == "host") return hostDeviceInfo();

  DeviceList list = listDevices();
  if (list.devices.empty()) {
    std::string msg =
        "no OpenCL device found: install an OpenCL driver, e.g. 'apt-get install pocl-opencl-icd'";
    for (const std::string& e : list.platformErrors) msg += "\n  " + e;
    throw RuntimeError(msg);
  }
  const auto& devs = list.devices;

  if (spec.empty()) {
    for (const DeviceInfo& d : devs)
      if (d.isGpu) return d;
    for (const DeviceInfo& d : devs)
      if (d.isCpu) return d;
    return devs.front();
  }

  static const std::regex indexForm(R"((\d{1,9}):(\d{1,9}))");
  std::smatch m;
  if (std::regex_match(spec, m, indexForm)) {
    int p = std::stoi(m[1].str()), i = std::stoi(m[2].str());
    for (const DeviceInfo& d : devs)
      if (d.platformIndex == p && d.deviceIndex == i) return d;
    throwNoMatch(spec);
  }

  const std::string needle = lower(spec);
  for (const DeviceInfo& d : devs)
    if (lower(d.name).find(needle) != std::string::npos) return d;
  for (const DeviceInfo& d : devs)
    if (lower(d.platformName).find(needle) != std::string::npos) return d;
  throwNoMatch(spec);
}

DeviceInfo selectOpenClDevice(const std::string& spec, const std::string& command) {
  DeviceInfo d = selectDevice(spec);
  if (d.isHost) throw InputError("--device " + spec + ": montecl " + command + " needs an OpenCL device");
  return d;
}

}  // namespace montecl
