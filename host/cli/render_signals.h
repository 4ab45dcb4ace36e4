// render_signals.h: how `montecl render` answers SIGINT and SIGTERM. While it loads (scene,
// textures, BVH, kernels, device tables: nothing written yet) a signal ends the process at once
// with 128 + signal (130, 143) and a line on stderr; once the waves run, the first signal stops
// the render after the current wave and the image so far is written (the exit status is then
// 128 + signal if the render stopped early, 0 if every wave had already completed), and a second
// one kills the process as usual (during the image write it is deferred until the file is
// complete: util/atomic_file.h). A signal the parent ignored (SIG_IGN, e.g. a background job of a
// script) stays ignored.
#pragma once
#include <signal.h>

namespace montecl {

// The signal that asked the render to stop (0: none); the wave loop reads it.
volatile int* renderInterruptFlag();
// Loading is over: a signal now stops the render gracefully instead of ending the process.
void endLoading();

// Installs the handlers for SIGINT and SIGTERM; restores the previous ones when destroyed.
// reinstall() puts them back after an OpenCL implementation replaced them (PoCL's LLVM installs
// its own when it loads).
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  void reinstall();

 private:
  struct sigaction previous_[2];
  bool installed_[2] = {false, false};
};

}  // namespace montecl
