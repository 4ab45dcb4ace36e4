// cmd_devices.cpp: `montecl devices [--json] [--check]`: lists every OpenCL device with the index
// (P:D) that --device accepts, then the host backend ("host"), plus any platform that failed to
// enumerate. No OpenCL device at all: exit 1. --check: also runs `montecl conformance` on them.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cl/device_tuning.h"
#include "cl/devices.h"
#include "cli/commands.h"
#include "conformance/conformance.h"
#include "util/errors.h"

namespace montecl {

namespace {

const char* kNoDevice =
    "no OpenCL device found: install an OpenCL driver, e.g. 'apt-get install pocl-opencl-icd'";

// The per-device kernel choices (cl/device_tuning.h).
nlohmann::json tuningJson(const DeviceTuning& t) {
  return {{"buildOptions", t.buildOptions}, {"workGroupSize", t.workGroupSize}, {"why", t.why},
          {"lanes", t.lanes}, {"lanesWhy", t.lanesWhy}};
}

std::string tuningText(const DeviceTuning& t) {
  std::string s = "work-group size " + std::to_string(t.workGroupSize) + ", lanes " + std::to_string(t.lanes) +
                  " (" + t.lanesWhy + ")";
  if (!t.buildOptions.empty()) s += ", " + t.buildOptions + " (" + t.why + ")";
  return s;
}

nlohmann::json deviceJson(const DeviceInfo& d) {
  if (d.isHost)
    return {{"index", "host"}, {"name", d.name}, {"type", d.typeName}, {"platform", d.platformName},
            {"computeUnits", d.computeUnits}};
  return {
      {"index", deviceIndexString(d)},
      {"platformIndex", d.platformIndex},
      {"deviceIndex", d.deviceIndex},
      {"name", d.name},
      {"vendor", d.vendor},
      {"type", d.typeName},
      {"platform", d.platformName},
      {"platformVersion", d.platformVersion},
      {"version", d.version},
      {"openclCVersion", d.openclCVersion},
      {"driverVersion", d.driverVersion},
      {"computeUnits", d.computeUnits},
      {"globalMemBytes", d.globalMemBytes},
      {"globalMem", formatBytes(d.globalMemBytes)},
      {"maxAllocBytes", d.maxAllocBytes},
      {"maxAlloc", formatBytes(d.maxAllocBytes)},
      {"maxWorkGroupSize", d.maxWorkGroupSize},
      {"tuning", tuningJson(deviceTuning(d))},
  };
}

void printText(const DeviceList& list) {
  for (const DeviceInfo& d : list.devices) {
    std::cout << deviceIndexString(d) << "  " << d.name << "\n"
              << "     platform:       " << d.platformName << " (" << d.platformVersion << ")\n"
              << "     vendor:         " << d.vendor << "\n"
              << "     type:           " << d.typeName << "\n"
              << "     OpenCL:         " << d.version << "; " << d.openclCVersion << "\n"
              << "     driver:         " << d.driverVersion << "\n"
              << "     compute units:  " << d.computeUnits << "\n"
              << "     global memory:  " << formatBytes(d.globalMemBytes) << "\n"
              << "     max allocation: " << formatBytes(d.maxAllocBytes) << "\n"
              << "     kernels:        " << tuningText(deviceTuning(d)) << "\n";
  }
  const DeviceInfo host = hostDeviceInfo();
  std::cout << "host " << host.name << "\n"
            << "     threads:        " << host.computeUnits << "\n";
  for (const std::string& e : list.platformErrors) std::cout << e << "\n";
}

}  // namespace

void addDevicesCommand(CLI::App& app, int& exitCode) {
  CLI::App* cmd = app.add_subcommand("devices", "List the OpenCL devices --device can select");
  auto json = std::make_shared<bool>(false);
  auto check = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "Print the list as a JSON array");
  cmd->add_flag("--check", *check, "Also run the conformance check (montecl conformance) on every device");
  cmd->callback([json, check, &exitCode]() {
    DeviceList list = listDevices();
    bool checkFailed = false;
    if (*json) {
      nlohmann::json arr = nlohmann::json::array();
      for (const DeviceInfo& d : list.devices) arr.push_back(deviceJson(d));
      arr.push_back(deviceJson(hostDeviceInfo()));
      if (*check) {
        ConformanceReport report = runConformance({});
        checkFailed = !report.pass;
        std::cout << nlohmann::json{{"devices", arr}, {"conformance", conformanceJson(report)}}.dump(2) << std::endl;
      } else {
        std::cout << arr.dump(2) << std::endl;
      }
      for (const std::string& e : list.platformErrors) std::cerr << e << "\n";
    } else {
      printText(list);
    }
    if (list.devices.empty()) throw RuntimeError(kNoDevice);
    exitCode = checkFailed ? kExitRuntime : kExitOk;
    if (*check && !*json) {
      ConformanceReport report = runConformance({});
      std::cout << "\n" << conformanceTable(report) << std::flush;
      if (!report.pass) exitCode = kExitRuntime;
    }
  });
}

}  // namespace montecl
