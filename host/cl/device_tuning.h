// device_tuning.h: what each OpenCL implementation runs the kernels best with, chosen from device
// queries (never from a setting the user must make): extra kernel build options and the default
// work-group size. Options here change speed only, never results (images stay bit-identical
// across devices: `montecl conformance`). docs/portability.md "Per-device choices"
// says why each one is there.
#pragma once
#include <cstddef>
#include <string>

#include "cl/devices.h"

namespace montecl {

struct DeviceTuning {
  std::string buildOptions;           // appended to every kernel build on the device ("" for none)
  std::size_t workGroupSize = 64;     // default local size (capped by CL_KERNEL_WORK_GROUP_SIZE)
  const char* why = "default";        // which rule matched, for `montecl devices`
};

// True for Intel's CPU OpenCL runtime (platform "Intel(R) OpenCL", a CPU device; PoCL on an Intel
// CPU is not it): its compiler packs consecutive work items into SIMD lanes.
bool isIntelCpuRuntime(const DeviceInfo& d);

DeviceTuning deviceTuning(const DeviceInfo& d);

}  // namespace montecl
