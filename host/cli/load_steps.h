// load_steps.h: the steps of `montecl render` before its first wave (reading the scene, textures,
// the BVH, kernels, the device tables): writes a line on stderr for a step that runs past about a
// second (and its time when it ends), so a long load is not a silent stall. Reads the test hook
// MONTECL_TEST_LOAD_PAUSE_S (seconds to wait inside the first step: tests signal a load with it).
#pragma once
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace montecl {

class LoadSteps {
 public:
  explicit LoadSteps(bool show);  // show: write the lines (not under -q)
  ~LoadSteps();
  LoadSteps(const LoadSteps&) = delete;
  LoadSteps& operator=(const LoadSteps&) = delete;
  void begin(const std::string& step);  // ends the step before
  void finish();                        // loading is over (no step runs)

 private:
  void watch();
  void endStep(std::unique_lock<std::mutex>& lock);
  bool show_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string step_;
  std::chrono::steady_clock::time_point start_;
  bool announced_ = false, done_ = false, paused_ = false;
  std::thread watcher_;
};

}  // namespace montecl
