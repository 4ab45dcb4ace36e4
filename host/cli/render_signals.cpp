// render_signals.cpp: the SIGINT / SIGTERM handlers of `montecl render` (render_signals.h). Writes
// one line on stderr when a signal ends a load.
#include "cli/render_signals.h"

#include <unistd.h>

#include <csignal>
#include <cstring>

namespace montecl {
namespace {

volatile int gInterrupted = 0;
volatile sig_atomic_t gLoading = 1;
constexpr int kSignals[2] = {SIGINT, SIGTERM};

void onInterrupt(int sig) {
  if (gLoading) {  // nothing is written yet: stop now (async-signal-safe calls only)
    const char* text = sig == SIGTERM ? "montecl: terminated while loading; nothing written\n"
                                      : "montecl: interrupted while loading; nothing written\n";
    ssize_t ignored = write(2, text, std::strlen(text));
    (void)ignored;
    _exit(128 + sig);
  }
  if (!gInterrupted) gInterrupted = sig;
  std::signal(sig, SIG_DFL);
}

bool signalInheritedIgnored(int sig) {
  struct sigaction sa {};
  return sigaction(sig, nullptr, &sa) == 0 && !(sa.sa_flags & SA_SIGINFO) && sa.sa_handler == SIG_IGN;
}

// The dispositions montecl inherited, read before main(): OpenCL implementations (PoCL's LLVM)
// install their own SIGINT/SIGTERM handlers when they load, replacing an inherited SIG_IGN.
const bool kInheritedIgnore[2] = {signalInheritedIgnored(SIGINT), signalInheritedIgnored(SIGTERM)};

void installHandler(int i) {
  struct sigaction sa {};
  sa.sa_handler = kInheritedIgnore[i] ? SIG_IGN : onInterrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(kSignals[i], &sa, nullptr);
}

}  // namespace

volatile int* renderInterruptFlag() { return &gInterrupted; }

void endLoading() { gLoading = 0; }

InterruptGuard::InterruptGuard() {
  for (int i = 0; i < 2; ++i) {
    if (sigaction(kSignals[i], nullptr, &previous_[i]) != 0) continue;
    installHandler(i);
    installed_[i] = true;
  }
}

InterruptGuard::~InterruptGuard() {
  for (int i = 0; i < 2; ++i)
    if (installed_[i]) sigaction(kSignals[i], &previous_[i], nullptr);
}

void InterruptGuard::reinstall() {
  // Only while loading: once a signal has arrived during the render its handler is SIG_DFL (a
  // second signal kills), which a reinstall must not undo.
  if (!gLoading) return;
  for (int i = 0; i < 2; ++i)
    if (installed_[i]) installHandler(i);
}

}  // namespace montecl
