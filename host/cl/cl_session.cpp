// cl_session.cpp: context, queue, cached program build and named kernel launches.
#include "cl/cl_session.h"

#include <algorithm>

#include "cl/cl_errors.h"
#include "cl/device_tuning.h"
#include "cl/kernel_source.h"
#include "util/errors.h"

namespace montecl {

ClSession::ClSession(const DeviceInfo& device, std::size_t workGroupSize, bool profiling,
                     const std::string& extraOptions, const std::string& programFile)
    : device_(device), oclgrind_(isOclgrind(device)), workGroupSize_(workGroupSize) {
  if (device.isHost)
    throw InputError("--device host: the host backend renders only (montecl render, conformance); this needs an "
                     "OpenCL device");
  context_ = cl::Context(device.device);
  queue_ = cl::CommandQueue(context_, device.device, profiling ? CL_QUEUE_PROFILING_ENABLE : 0);
  const DeviceTuning tuning = deviceTuning(device);
  if (workGroupSize_ == 0) workGroupSize_ = tuning.workGroupSize;
  std::string options = kKernelBuildOptions;
  if (!extraOptions.empty()) options += " " + extraOptions;
  // What this OpenCL implementation runs best (cl/device_tuning.h); never changes results.
  if (!tuning.buildOptions.empty()) options += " " + tuning.buildOptions;
  // Oclgrind 21.10 (Debian) aborts on the LLVM `freeze` instructions of optimised kernels.
  if (oclgrind_) options += " -cl-opt-disable";
  // Division and sqrt correctly rounded where the device can (OpenCL 1.2 allows 2.5 / 3 ulp by
  // default, and NVIDIA's compiler uses those approximations: light-sampled images differed from
  // the host backend by 6e-4 relative on an H200). CPUs round them correctly anyway.
  if (device.device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT)
    options += " -cl-fp32-correctly-rounded-divide-sqrt";
  build_ = buildProgramCached(context_, device, expandedKernelSource(programFile), options);
}

cl::Kernel ClSession::kernel(const char* name) const {
  try {
    return cl::Kernel(build_.program, name);
  } catch (const cl::Error& e) {
    throw RuntimeError(std::string("kernel ") + name + ": " + describeClError(e));
  }
}

std::size_t ClSession::localSize(const cl::Kernel& k) const {
  std::size_t maxSize = k.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device_.device);
  return std::max<std::size_t>(1, std::min(workGroupSize_, maxSize));
}

void ClSession::launch(cl::Kernel& k, std::uint64_t n, cl::Event* event, std::size_t local) {
  if (n == 0) return;
  local = local ? std::min(local, localSize(k)) : localSize(k);
  std::size_t global = ((n + local - 1) / local) * local;
  try {
    queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NDRange(local), nullptr, event);
  } catch (const cl::Error& e) {
    throw RuntimeError("kernel " + k.getInfo<CL_KERNEL_FUNCTION_NAME>() + ": " + describeClError(e));
  }
}

double ClSession::launchTimed(cl::Kernel& k, std::uint64_t n) {
  if (n == 0) return 0.0;
  std::size_t local = localSize(k);
  std::size_t global = ((n + local - 1) / local) * local;
  cl::Event ev;
  try {
    queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NDRange(local), nullptr, &ev);
    ev.wait();
  } catch (const cl::Error& e) {
    throw RuntimeError("kernel " + k.getInfo<CL_KERNEL_FUNCTION_NAME>() + ": " + describeClError(e));
  }
  cl_ulong start = ev.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  cl_ulong end = ev.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return double(end - start) * 1e-6;
}

}  // namespace montecl
