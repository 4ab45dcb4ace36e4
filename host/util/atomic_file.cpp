// atomic_file.cpp: writeAtomically: the writer fills a uniquely named temporary file next to the
// target (same folder, so the rename cannot cross filesystems; same extension, so format-by-name
// libraries such as OpenImageIO still see ".png"), which is then renamed over the target. Any
// failure removes the temporary and leaves an existing target untouched.
#include "util/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <system_error>

#include "util/errors.h"

namespace montecl {
namespace fs = std::filesystem;

namespace {

std::string tempPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  fs::path p(path);
  std::string name = "." + p.filename().string() + ".tmp" + std::to_string(::getpid()) + "_" +
                     std::to_string(counter.fetch_add(1)) + p.extension().string();
  return (p.parent_path() / name).string();
}

void removeQuietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace

void writeAtomically(const std::string& path,
                     const std::function<void(const std::string&)>& write) {
  const std::string tmp = tempPathFor(path);
  try {
    write(tmp);
  } catch (...) {
    removeQuietly(tmp);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    removeQuietly(tmp);
    throw RuntimeError(path + ": cannot write: " + ec.message());
  }
}

}  // namespace montecl
