// cl_session.h: one OpenCL context + in-order queue on a device, with one kernel program (a file
// under kernels/, expanded, plus extra build options) built through the program cache, and kernel
// launches that name the kernel when they fail. Knows nothing of what the program computes.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "cl/devices.h"
#include "cl/program_cache.h"

namespace montecl {

constexpr const char* kKernelBuildOptions = "-cl-std=CL1.2";

class ClSession {
 public:
  // Builds kernels/<programFile> with kKernelBuildOptions + " " + extraOptions (e.g. defines),
  // then the device's own options (cl/device_tuning.h). workGroupSize 0: the device's default
  // (64), capped by CL_KERNEL_WORK_GROUP_SIZE per kernel. profiling: the queue is created with
  // CL_QUEUE_PROFILING_ENABLE (event timings, used by `montecl bench`).
  explicit ClSession(const DeviceInfo& device, std::size_t workGroupSize = 0, bool profiling = false,
                     const std::string& extraOptions = "", const std::string& programFile = "montecl.cl");

  const DeviceInfo& device() const { return device_; }
  const cl::Context& context() const { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  const ProgramBuild& build() const { return build_; }
  cl::Kernel kernel(const char* name) const;

  // Launches k over n work items (global size rounded up to whole work-groups); event: receives
  // the launch's event (left empty when n is 0).
  // local: the work-group size (0: localSize(k), the tuned one).
  void launch(cl::Kernel& k, std::uint64_t n, cl::Event* event = nullptr, std::size_t local = 0);
  // Launches k over n work items, waits, and returns its execution time in ms from the event's
  // profiling info (the session must have been created with profiling).
  double launchTimed(cl::Kernel& k, std::uint64_t n);
  std::size_t localSize(const cl::Kernel& k) const;

  template <typename T>
  cl::Buffer upload(const std::vector<T>& data, cl_mem_flags flags = CL_MEM_READ_ONLY) const {
    if (data.empty()) return buffer<T>(1, flags);  // OpenCL has no empty buffers
    return cl::Buffer(context_, flags | CL_MEM_COPY_HOST_PTR, data.size() * sizeof(T), const_cast<T*>(data.data()));
  }
  template <typename T>
  cl::Buffer buffer(std::size_t count, cl_mem_flags flags = CL_MEM_READ_WRITE) const {
    return cl::Buffer(context_, flags, std::max<std::size_t>(1, count) * sizeof(T));
  }
  // A buffer that kernels write and later kernels read (rays, hits, queues of a wave), which the
  // host neither writes nor reads. On a real device it is left uninitialised, like buffer(). On
  // Oclgrind it is created from a host copy of kScratchCanary words: Oclgrind 21.10's
  // --uninitialized check keeps the shadow (definedness) memory of a released buffer and hands it,
  // with the old size, to the next buffer that gets the same slot, so a bigger buffer in a reused
  // slot reads as uninitialised past the old size (and kernel stores there are lost); one host
  // write of the whole buffer, at offset 0, resets the shadow to the buffer's size, all defined.
  // The canary keeps the check's point: a kernel that reads an element no kernel wrote gets a NaN
  // (the image differs from the host backend's) or, as an index, an address Oclgrind reports as
  // out of bounds.
  template <typename T>
  cl::Buffer scratch(std::size_t count) const {
    static_assert(sizeof(T) % sizeof(cl_uint) == 0, "scratch: whole 32-bit words");
    if (!oclgrind_) return buffer<T>(count);
    std::vector<cl_uint> canary(std::max<std::size_t>(1, count) * sizeof(T) / sizeof(cl_uint), kScratchCanary);
    return upload(canary, CL_MEM_READ_WRITE);
  }
  // Oclgrind's scratch fill: a quiet NaN as a float, 2^31 - 2^22 (far out of bounds) as an index.
  static constexpr cl_uint kScratchCanary = 0x7fc00000u;

 private:
  DeviceInfo device_;
  bool oclgrind_;
  std::size_t workGroupSize_;
  cl::Context context_;
  cl::CommandQueue queue_;
  ProgramBuild build_;
};

}  // namespace montecl
