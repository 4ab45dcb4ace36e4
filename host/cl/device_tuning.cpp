// device_tuning.cpp: per-device build options and work-group size from device queries
// (device_tuning.h). Measured on a 2-core AMD EPYC (docs/portability.md, "Per-device choices").
#include "cl/device_tuning.h"

#include "util/errors.h"

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
  if (isOclgrind(d)) {
    // Oclgrind 21.10 checks the packet stages at W = 1 only: with W = 4 its --uninitialized check
    // reports film and queue stores of the packet code as uninitialised (the same renders are bit
    // for bit the host backend's on PoCL at every W; suspected: its shadow tracking through vector
    // shuffles), and it segfaults with W = 16 (or W = 4 with the typed vector loads of lanes.h).
    t.lanes = 1;
    t.lanesWhy = "Oclgrind: packet stages checked at W = 1";
  } else if (d.isCpu && !d.isHost) {
    // PoCL compiles each work item as written (it vectorised none of the stage kernels across
    // work items), so the packet stages fill the CPU's vector registers themselves: float16 on
    // AVX-512 (PoCL's device name and HSTR say "avx512"; its native float vector width is 16).
    cl_uint native = 0;
    try {
      if (d.device()) native = d.device.getInfo<CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT>();
    } catch (const cl::Error&) {
    }
    const bool avx512 = d.name.find("avx512") != std::string::npos || d.version.find("avx512") != std::string::npos;
    if (avx512 || native >= 16) {
      t.lanes = 16;
      t.lanesWhy = "CPU with AVX-512: float16 packets";
    } else if (native == 4) {
      t.lanes = 4;
      t.lanesWhy = "CPU with 4-wide float vectors: float4 packets";
    } else {
      t.lanes = 8;
      t.lanesWhy = "CPU: float8 packets";
    }
  }
  if (d.isCpu && !d.isHost && !isOclgrind(d)) {
    // Prefetch hints in the wide traversal (kernels/shared/traverse_wide.h): a large scene's tree
    // misses the caches, and the loads of the children a ray will pop later overlap its work.
    t.buildOptions += t.buildOptions.empty() ? "-DMCL_PREFETCH_HINTS=1" : " -DMCL_PREFETCH_HINTS=1";
  }
  return t;
}

unsigned resolveLanes(unsigned requested, const DeviceInfo& device) {
  if (requested != 0 && requested != 1 && requested != 4 && requested != 8 && requested != 16)
    throw InputError("--lanes " + std::to_string(requested) + ": must be 1, 4, 8 or 16");
  if (device.isHost) return 1;
  return requested != 0 ? requested : deviceTuning(device).lanes;
}

}  // namespace montecl
