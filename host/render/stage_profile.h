// stage_profile.h: where a render's time goes (`montecl render --profile`). Each stage launch's
// execution time (OpenCL profiling events in the OpenCL backend, host timers in the host backend)
// is summed per stage name from the stage table (a stage launched on the bounce rays counts
// separately, e.g. "intersect (bounce rays)"), so new stages appear without changes here.
// formatProfile prints each stage's share of the render's wall time; the rest of the wall time,
// when the device ran no stage (host code, transfers, waits, queue latency), is its own row.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "render/stage_bindings.h"

namespace montecl {

struct StageTime {
  std::string name;
  double ms = 0.0;
  std::uint64_t launches = 0;
};

struct StageProfile {
  std::vector<StageTime> stages;  // in the order of their first launch
  // The shading stages' hits shaded in lane types and one by one (FrameParams::countLanes).
  std::uint64_t packedLanes = 0, aloneLanes = 0;
  void add(const std::string& name, double ms);
  double stageMs() const;  // the sum over stages
};

// The profile's name of a launch of stage s on `rays`.
std::string stageProfileName(Stage s, RayInput rays);

// The table `--profile` prints: one row per stage (ms, share of wallSeconds, launches), one row
// "host (device idle)" with the rest of the wall time, and the total (100%); then the share of
// the shading stages' hits shaded in lane types.
std::string formatProfile(const StageProfile& profile, double wallSeconds);

}  // namespace montecl
