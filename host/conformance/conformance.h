// conformance.h: `montecl conformance`: renders the conformance set (conformance/scenes.h) on
// each OpenCL device and on the host backend, and compares every image with the host's pixel by
// pixel. A pixel channel passes when |device - host| <= max(kRelTolerance * max(|device|, |host|),
// kAbsFloor): 1e-5 relative, with an absolute floor of 1e-6 (radiance units; the scenes' values
// are O(0.1 .. 10)) so that pixels that are 0 on one side and a rounding residue on the other do
// not fail on a meaningless relative difference.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bvh/bvh_layout.h"
#include "conformance/scenes.h"

namespace montecl {

constexpr double kRelTolerance = 1e-5;
constexpr double kAbsFloor = 1e-6;

struct ImageComparison {
  std::string name;
  int width = 0, height = 0, spp = 0;
  double maxAbsDiff = 0.0, meanAbsDiff = 0.0, maxRelDiff = 0.0;
  std::uint64_t failingValues = 0;  // pixel channels over the tolerance
  std::uint64_t differingBits = 0;  // film channels (mean, M2: hi and lo, rgb) whose bits differ from the host's
  double mrays = 0.0;               // this device's Mrays/s on the image
  double seconds = 0.0;
  bool rendered = false, pass = false;
  std::string error;
};

struct DeviceReport {
  std::string index, name, platform;
  bool buildOk = false;
  double buildMs = 0.0;
  bool fromCache = false;
  std::string buildError;
  std::vector<ImageComparison> images;
  bool pass = false;
};

struct ConformanceReport {
  std::vector<DeviceReport> devices;
  std::vector<std::string> skipped;  // cases left out (missing scene files)
  std::vector<std::string> platformErrors;
  double hostMrays = 0.0;  // the host backend over the whole set
  bool pass = false;
};

struct ConformanceOptions {
  std::vector<std::string> deviceSpecs;  // empty: every OpenCL device found
  BvhLayout bvhLayout = BvhLayout::Auto;  // of the OpenCL devices; the host backend runs wide
  unsigned lanes = 0;  // packet stages' width on the OpenCL devices (0: each device's own)
  ConformanceSetOptions set;
};

ConformanceReport runConformance(const ConformanceOptions& options);
nlohmann::json conformanceJson(const ConformanceReport& report);
std::string conformanceTable(const ConformanceReport& report);

}  // namespace montecl
