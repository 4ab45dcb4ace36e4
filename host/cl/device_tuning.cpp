// device_tuning.cpp: per-device build options and work-group size from device queries
// (device_tuning.h). Measured on a 2-core AMD EPYC (docs/portability.md, "Per-device choices").
#include "cl/device_tuning.h"

namespace montecl {

bool isIntelCpuRuntime(const DeviceInfo& d) {
  return !d.isHost && d.isCpu && d.platformName.find("Intel(R) OpenCL") != std::string::npos;
}

DeviceTuning deviceTuning(const DeviceInfo& d) {
  DeviceTuning t;
  if (isIntelCpuRuntime(d)) {
    // Intel's compiler runs 8 or 16 work items in the lanes of one SIMD register (implicit
    // vectorisation). The traversal loops diverge per ray (each lane its own stack and node), so
    // the packed kernels ran 2-4x slower than one item per core thread; and the glossy
    // conformance images from packed kernels differ from the host backend (cause not found).
    // -DMCL_SCALAR_WORK_ITEMS puts vec_type_hint(float8) on the kernels (kernels/montecl.cl),
    // which turns the packing off: each work item runs as written, with its own float8 box test.
    t.buildOptions = "-DMCL_SCALAR_WORK_ITEMS=1";
    t.why = "Intel CPU runtime: one work item per thread (no packing across work items)";
  }
  return t;
}

}  // namespace montecl
