// devices.h: enumerating OpenCL platforms/devices and choosing one from a --device SPEC (or the
// host backend, "host").
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cl/opencl.h"

namespace montecl {

struct DeviceInfo {
  bool isHost = false;  // the host backend (`--device host`): no OpenCL; `device` is null
  int platformIndex = 0;
  int deviceIndex = 0;
  std::string platformName, platformVersion;
  std::string name, vendor, version, driverVersion, openclCVersion;
  bool isGpu = false, isCpu = false;
  std::string typeName;  // "GPU", "CPU", "accelerator", "custom" (joined with '+' if several)
  std::uint32_t computeUnits = 0;
  std::uint64_t globalMemBytes = 0, maxAllocBytes = 0;
  std::size_t maxWorkGroupSize = 0;
  cl::Device device;
};

struct DeviceList {
  std::vector<DeviceInfo> devices;
  // "platform 1 (<name>): OpenCL call clGetDeviceIDs failed: CL_... (-n)"
  std::vector<std::string> platformErrors;
};

// Every device of every platform; a platform that fails is reported in platformErrors, not thrown.
DeviceList listDevices();

// The host backend: the stage functions run as C++ on the CPU (render/host_backend.cpp).
DeviceInfo hostDeviceInfo();

// Chooses a device: spec "host" (case-insensitive) for the host backend, which needs no OpenCL
// driver; spec "P:D", or a case-insensitive substring of the device or platform name;
// empty spec: first GPU, else first CPU, else first device. Throws InputError when the spec matches
// nothing, RuntimeError when there is no OpenCL device at all (saying to install pocl-opencl-icd).
DeviceInfo selectDevice(const std::string& spec);

// selectDevice for commands that need a real OpenCL device: "host" is an InputError naming the
// command ("--device host: montecl bench needs an OpenCL device").
DeviceInfo selectOpenClDevice(const std::string& spec, const std::string& command);

// True for the Oclgrind simulator's device (its platform is named "Oclgrind"), which
// ClSession::scratch treats specially (see there).
bool isOclgrind(const DeviceInfo& d);

// "P:D", the index form of a device accepted by selectDevice ("host" for the host backend).
std::string deviceIndexString(const DeviceInfo& d);

// Human-readable byte count: "512 B", "64.0 KiB", "3.7 GiB".
std::string formatBytes(std::uint64_t bytes);

}  // namespace montecl
