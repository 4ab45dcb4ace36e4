// cl_errors.h: names of OpenCL error codes and the one-line report of a failed OpenCL call.
#pragma once
#include <string>

#include "cl/opencl.h"

namespace montecl {

// "CL_OUT_OF_RESOURCES" for -5, ...; "CL_ERROR(<n>)" for unknown codes.
const char* clErrorName(cl_int code);

// "OpenCL call clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5)"
std::string describeClError(const cl::Error& e);

}  // namespace montecl
