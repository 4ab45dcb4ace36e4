// cl_session.h: one OpenCL context + in-order queue on a device, with montecl's kernel program
// (kernels/montecl.cl) built through the program cache, and kernel launches that name the kernel
// when they fail.
#pragma once
#include <cstdint>
#include <string>

#include "bvh/bvh_layout.h"
#include "cl/devices.h"
#include "cl/program_cache.h"

namespace montecl {

constexpr const char* kKernelBuildOptions = "-cl-std=CL1.2";

class ClSession {
 public:
  // workGroupSize 0: min(64, CL_KERNEL_WORK_GROUP_SIZE) per kernel. profiling: the queue is
  // created with CL_QUEUE_PROFILING_ENABLE (event timings, used by `montecl bench`). layout: the
  // BVH the kernels traverse (Auto: by device type, resolveBvhLayout).
  explicit ClSession(const DeviceInfo& device, std::size_t workGroupSize = 0, bool profiling = false,
                     BvhLayout layout = BvhLayout::Auto);

  const DeviceInfo& device() const { return device_; }
  BvhLayout layout() const { return layout_; }  // resolved: Wide or Binary
  const cl::Context& context() const { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  const ProgramBuild& build() const { return build_; }
  cl::Kernel kernel(const char* name) const;

  // Launches k over n work items (global size rounded up to whole work-groups).
  void launch(cl::Kernel& k, std::uint64_t n);
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

 private:
  DeviceInfo device_;
  std::size_t workGroupSize_;
  BvhLayout layout_;
  cl::Context context_;
  cl::CommandQueue queue_;
  ProgramBuild build_;
};

}  // namespace montecl
