// opencl.h: the one place that includes CLHPP, with the version macros set by CMake.
#pragma once
#include <CL/opencl.hpp>
