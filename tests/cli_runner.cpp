// cli_runner.cpp: runs the real montecl executable (MONTECL_EXE), or any program, with posix_spawn,
// stdout and stderr redirected to temporary files and optional extra environment variables, and
// provides TempDir, a per-test scratch folder.
#include "cli_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace montecl_test {
namespace {

constexpr auto kTimeout = std::chrono::seconds(300);

std::string tempRoot() {
  const char* t = std::getenv("TMPDIR");
  return (t && *t) ? t : "/tmp";
}

// An unlinked-on-destruction temp file opened for writing, used to capture one output stream.
struct CaptureFile {
  CaptureFile() {
    path = tempRoot() + "/montecl-cli-XXXXXX";
    fd = ::mkostemp(&path[0], O_CLOEXEC);  // the child gets it only through dup2
    if (fd < 0) throw std::runtime_error("mkostemp failed for " + path);
  }
  ~CaptureFile() {
    if (fd >= 0) ::close(fd);
    ::unlink(path.c_str());
  }
  std::string read() const {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::string path;
  int fd = -1;
};

// Waits for pid, killing it after kTimeout; returns the exit code or 128 + signal.
int waitWithTimeout(pid_t pid) {
  auto deadline = std::chrono::steady_clock::now() + kTimeout;
  int status = 0;
  for (;;) {
    pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw std::runtime_error("waitpid failed");
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace

CliResult runProgram(const std::vector<std::string>& args, const std::vector<std::string>& extraEnv) {
  CaptureFile out, err;
  std::vector<std::string> argvStore = args;
  std::vector<char*> argv;
  for (std::string& a : argvStore) argv.push_back(&a[0]);
  argv.push_back(nullptr);

  // The parent's environment, minus the names extraEnv sets, plus extraEnv.
  std::vector<std::string> envStore;
  for (char** e = environ; *e; ++e) {
    std::string entry = *e;
    bool replaced = false;
    for (const std::string& x : extraEnv)
      if (entry.compare(0, x.find('=') + 1, x, 0, x.find('=') + 1) == 0) replaced = true;
    if (!replaced) envStore.push_back(entry);
  }
  envStore.insert(envStore.end(), extraEnv.begin(), extraEnv.end());
  std::vector<char*> envp;
  for (std::string& e : envStore) envp.push_back(&e[0]);
  envp.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out.fd, 1);
  posix_spawn_file_actions_adddup2(&actions, err.fd, 2);
  pid_t pid = 0;
  int rc = ::posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error(std::string("cannot run ") + argv[0]);

  CliResult result;
  result.exitCode = waitWithTimeout(pid);
  result.out = out.read();
  result.err = err.read();
  return result;
}

CliResult runMontecl(const std::vector<std::string>& args, const std::vector<std::string>& extraEnv) {
  std::vector<std::string> argv{MONTECL_EXE};
  argv.insert(argv.end(), args.begin(), args.end());
  return runProgram(argv, extraEnv);
}

TempDir::TempDir() {
  std::string templ = tempRoot() + "/montecl-test-XXXXXX";
  if (!::mkdtemp(&templ[0])) throw std::runtime_error("mkdtemp failed for " + templ);
  path = templ;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);  // best effort; a destructor must not throw
}

void TempDir::write(const std::string& name, const std::string& text) const {
  std::filesystem::path p = std::filesystem::path(path) / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream f(p, std::ios::binary);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + p.string());
}

std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace montecl_test
