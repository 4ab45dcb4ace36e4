// atomic_file.h: write a file through a temporary in the same folder, then rename over the target,
// so a failure never leaves a partial file.
#pragma once
#include <functional>
#include <string>

namespace montecl {

// Calls write(tmpPath); on success renames tmpPath to path, on any exception removes tmpPath and
// rethrows. tmpPath keeps path's extension (e.g. "out.png" -> ".out.png.tmp12345.png").
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace montecl
