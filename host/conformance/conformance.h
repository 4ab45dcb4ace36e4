// conformance.h: `montecl conformance`: renders the conformance set (conformance/scenes.h) on
// each OpenCL device and on the host backend, and compares every image with the host's: an image
// passes only when every film value (mean and M2, both float-float halves, the sample counts and
// the AOV sums) has the host's bits. How far a failing image is is reported as differences, and
// values beyond max(kRelTolerance * max(|device|, |host|), kAbsFloor) (1e-5 relative, absolute
// floor 1e-6) are counted as gross errors.
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
