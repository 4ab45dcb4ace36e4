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
  // Lanes of the packet stages (kernels/shared/lanes.h, -DMCL_LANES=W): 16 on CPUs with AVX-512,
  // 8 on other CPUs (4 where the native float vector is 4 wide), 1 on GPUs (and any other device).
  unsigned lanes = 1;
  const char* lanesWhy = "not a CPU: one item per work item";
};

// The packet width W the stages of `device` are built for: `requested` when it is not 0 (one of
// 1, 4, 8, 16; else InputError), otherwise deviceTuning(device).lanes. The host backend: 1.
unsigned resolveLanes(unsigned requested, const DeviceInfo& device);

// True for Intel's CPU OpenCL runtime (platform "Intel(R) OpenCL", a CPU device; PoCL on an Intel
// CPU is not it): its compiler packs consecutive work items into SIMD lanes.
bool isIntelCpuRuntime(const DeviceInfo& d);

DeviceTuning deviceTuning(const DeviceInfo& d);

}  // namespace montecl
