// atomic_file.h: write a file through a temporary in the same folder, then rename over the target,
// so a failure never leaves a partial file; check before long work that the target can be written.
#pragma once
#include <functional>
#include <string>

namespace montecl {

// Calls write(tmpPath); on success renames tmpPath to path, on any exception removes tmpPath and
// rethrows. tmpPath keeps path's extension (e.g. "out.png" -> ".out.png.tmp12345_0.png"; the name
// part is shortened when the whole would exceed NAME_MAX).
// Before writing, temporaries of this same target left by dead processes (killed during a write:
// SIGKILL, power loss) are removed: exactly the names tempFileName() gives for a PID that is no
// longer alive. SIGINT, SIGTERM and SIGHUP arriving during the write and rename are deferred
// (unless ignored) and re-raised afterwards, so a signal never leaves a temporary behind.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);

// The temporary's file name (no folder) for target file name `name`, process pid, counter n.
std::string tempFileName(const std::string& name, long pid, unsigned n);

// Throws InputError "<path>: cannot write <role>: <why>" unless a file can be written at path:
// the folder exists and accepts a new file (probed by creating and removing a temporary), the
// name fits NAME_MAX, and path is not a folder. Call before rendering.
void checkWritableTarget(const std::string& path, const std::string& role = "the output");

}  // namespace montecl
