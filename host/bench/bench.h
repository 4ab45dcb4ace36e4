// bench.h: `montecl bench`: BVH build statistics, device traversal throughput per ray kind timed
// with OpenCL profiling events, correctness against the host reference traversal, and the same
// build and rays on Embree 3 for comparison. The result is printed as a table and/or JSON.
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "bvh/bvh.h"

namespace montecl {

struct BenchOptions {
  std::string scene;
  std::string device;            // --device SPEC ("" = default device)
  std::string jsonPath;          // "" = no JSON file
  int repeat = 5;                // timed repetitions per kernel (after `warmup` untimed ones)
  int warmup = 1;
  unsigned threads = 0;          // Embree and host reference threads; 0 = the device's compute units
  std::optional<int> width, height;  // override the scene's resolution
  std::size_t workGroupSize = 0; // 0 = ClSession's default
  std::string bvhLayout = "auto";  // auto | wide | binary (bvh/bvh_layout.h)
  bool embree = true;            // --no-embree skips the comparison
  bool sahReference = false;     // --sah-reference: also the full-sweep SAH cost (slow: seconds)
  float splitBudget = BvhBuildOptions{}.splitBudget;  // --split-budget (bvh.h)
  double relTolerance = 1e-4;    // a hit distance differing by more than this (relative) mismatches
};

// Runs the whole bench; returns the JSON document described in bench.cpp. Prints progress to
// stderr when verbose.
nlohmann::json runBench(const BenchOptions& options, bool verbose);

// The readable table of a runBench() result.
std::string formatBenchTable(const nlohmann::json& result);

}  // namespace montecl
