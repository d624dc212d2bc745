#include "cli/interrupt.h"

#include <csignal>

namespace tray {
namespace {

std::atomic<bool> gStop{false};
std::atomic<int> gSignal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "signal handlers may only touch lock-free atomics");

extern "C" void onInterrupt(int sig) {
  int none = 0;
  gSignal.compare_exchange_strong(none, sig);
  gStop.store(true);
  std::signal(sig, SIG_DFL);  // async-signal-safe; a second signal stops at once
}

}  // namespace

const std::atomic<bool>& installInterruptHandlers() {
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  return gStop;
}

int interruptSignal() {
  return gSignal.load();
}

}  // namespace tray
