// load_steps.cpp: LoadSteps (load_steps.h): a watcher thread that announces a load step once it
// has run for a second, and the step's time when it ends. Writes stderr only.
#include "cli/load_steps.h"

#include <cstdio>
#include <cstdlib>

namespace montecl {
namespace {

constexpr std::chrono::milliseconds kQuiet(1000);  // steps shorter than this say nothing

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

LoadSteps::LoadSteps(bool show) : show_(show) {
  if (show_) watcher_ = std::thread([this] { watch(); });
}

LoadSteps::~LoadSteps() {
  finish();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  if (watcher_.joinable()) watcher_.join();
}

void LoadSteps::endStep(std::unique_lock<std::mutex>&) {
  if (announced_ && show_) std::fprintf(stderr, "montecl: %s: done in %.1f s\n", step_.c_str(), secondsSince(start_));
  step_.clear();
  announced_ = false;
}

void LoadSteps::begin(const std::string& step) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    endStep(lock);
    step_ = step;
    start_ = std::chrono::steady_clock::now();
  }
  wake_.notify_all();
  // The test hook: a pause inside the first step, long enough for a test to see the step's line
  // and to signal the process while it loads.
  if (!paused_) {
    paused_ = true;
    if (const char* pause = std::getenv("MONTECL_TEST_LOAD_PAUSE_S"))
      std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(pause)));
  }
}

void LoadSteps::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  endStep(lock);
}

void LoadSteps::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!done_) {
    if (step_.empty() || announced_) {
      wake_.wait(lock);
      continue;
    }
    const auto due = start_ + kQuiet;
    if (std::chrono::steady_clock::now() < due) {
      wake_.wait_until(lock, due);
      continue;
    }
    std::fprintf(stderr, "montecl: %s ...\n", step_.c_str());
    announced_ = true;
  }
}

}  // namespace montecl
