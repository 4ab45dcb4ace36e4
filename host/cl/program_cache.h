// program_cache.h: builds an OpenCL program, reusing a binary cached on disk when one matches.
// Cache folder: $MONTECL_CACHE_DIR, else $XDG_CACHE_HOME/montecl, else ~/.cache/montecl.
// Key: hash of platform name+version, device name, driver version, build options and the full
// (include-expanded) source. A failed build throws RuntimeError carrying the build log.
#pragma once
#include <string>

#include "cl/devices.h"

namespace montecl {

struct ProgramBuild {
  cl::Program program;
  bool fromCache = false;
  double buildMs = 0.0;
  std::string cachePath;
};

std::string programCacheDir();

ProgramBuild buildProgramCached(const cl::Context& context, const DeviceInfo& device,
                                const std::string& source, const std::string& options);

}  // namespace montecl
