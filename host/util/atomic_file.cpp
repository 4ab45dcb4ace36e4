// atomic_file.cpp: writeAtomically: the writer fills a uniquely named temporary file next to the
// target (same folder, so the rename cannot cross filesystems; same extension, so format-by-name
// libraries such as OpenImageIO still see ".png"), which is then renamed over the target. Any
// failure removes the temporary and leaves an existing target untouched. Termination signals are
// deferred while the temporary exists; temporaries of dead processes are swept before a write.
#include "util/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <regex>
#include <system_error>

#include "util/errors.h"

namespace montecl {
namespace fs = std::filesystem;

namespace {

#ifndef NAME_MAX
#define NAME_MAX 255
#endif

std::atomic<unsigned> gCounter{0};

std::string tempPathFor(const std::string& path) {
  fs::path p(path);
  return (p.parent_path() / tempFileName(p.filename().string(), long(::getpid()), gCounter.fetch_add(1))).string();
}

void removeQuietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

bool processAlive(long pid) { return pid > 0 && (::kill(pid_t(pid), 0) == 0 || errno != ESRCH); }

// Removes temporaries of target `path` whose writer process is gone (never our own).
void sweepStaleTemps(const std::string& path) {
  fs::path p(path);
  const std::string name = p.filename().string();
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  static const std::regex pattern(R"(^\..*\.tmp([0-9]{1,10})_([0-9]{1,10})(\.[^.]*)?$)");
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  if (ec) return;
  for (; it != end; it.increment(ec)) {
    if (ec) return;
    const std::string entry = it->path().filename().string();
    std::smatch m;
    if (entry.size() < 2 || entry[0] != '.' || !std::regex_match(entry, m, pattern)) continue;
    const long pid = std::stol(m[1].str());
    const unsigned long n = std::stoul(m[2].str());
    if (pid == long(::getpid()) || n > UINT_MAX || entry != tempFileName(name, pid, unsigned(n))) continue;
    if (processAlive(pid)) continue;
    std::error_code rm;
    fs::remove(it->path(), rm);
  }
}

// Termination signals received while a temporary exists: recorded, then re-raised once it is gone.
const int kDeferredSignals[] = {SIGINT, SIGTERM, SIGHUP};
volatile sig_atomic_t gDeferred[3] = {0, 0, 0};

void recordSignal(int sig) {
  for (int i = 0; i < 3; ++i)
    if (kDeferredSignals[i] == sig) gDeferred[i] = 1;
}

class SignalDeferral {
 public:
  SignalDeferral() {
    for (int i = 0; i < 3; ++i) {
      gDeferred[i] = 0;
      installed_[i] = false;
      if (::sigaction(kDeferredSignals[i], nullptr, &old_[i]) != 0) continue;
      if (!(old_[i].sa_flags & SA_SIGINFO) && old_[i].sa_handler == SIG_IGN) continue;  // ignored stays ignored
      struct sigaction sa {};
      sa.sa_handler = recordSignal;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags = SA_RESTART;
      installed_[i] = ::sigaction(kDeferredSignals[i], &sa, nullptr) == 0;
    }
  }
  ~SignalDeferral() {
    for (int i = 0; i < 3; ++i)
      if (installed_[i]) ::sigaction(kDeferredSignals[i], &old_[i], nullptr);
    for (int i = 0; i < 3; ++i)
      if (installed_[i] && gDeferred[i]) ::raise(kDeferredSignals[i]);  // now with the previous disposition
  }
  SignalDeferral(const SignalDeferral&) = delete;
  SignalDeferral& operator=(const SignalDeferral&) = delete;

 private:
  struct sigaction old_[3];
  bool installed_[3];
};

}  // namespace

std::string tempFileName(const std::string& name, long pid, unsigned n) {
  const std::string ext = fs::path(name).extension().string();
  const std::string tail = ".tmp" + std::to_string(pid) + "_" + std::to_string(n) + ext;
  std::string stem = name;
  const std::size_t room = NAME_MAX > 1 + tail.size() ? NAME_MAX - 1 - tail.size() : 0;
  if (stem.size() > room) stem.resize(room);
  return "." + stem + tail;
}

void writeAtomically(const std::string& path,
                     const std::function<void(const std::string&)>& write) {
  sweepStaleTemps(path);
  SignalDeferral deferral;
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

void checkWritableTarget(const std::string& path, const std::string& role) {
  fs::path p(path);
  const std::string name = p.filename().string();
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  auto fail = [&](const std::string& why) { throwInputError(path, "", "cannot write " + role + ": " + why); };
  if (name.empty() || name == "." || name == "..") fail("no file name");
  if (name.size() > NAME_MAX)
    fail("file name is " + std::to_string(name.size()) + " bytes, more than the " + std::to_string(NAME_MAX) +
         " a name may have");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail("folder '" + dir.string() + "' does not exist");
  if (fs::is_directory(p, ec)) fail("it is a folder");
  const std::string probe = (dir / tempFileName(name, long(::getpid()), gCounter.fetch_add(1))).string();
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) fail(std::string("cannot create a file in '") + dir.string() + "': " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace montecl
