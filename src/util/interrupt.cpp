#include "util/interrupt.h"

#include <atomic>

namespace radiant {

namespace {
// A lock-free atomic int is the one object a signal handler may write.
std::atomic<int> pendingSignal{0};
static_assert(std::atomic<int>::is_always_lock_free);
}  // namespace

bool interruptRequested() {
  return pendingSignal.load(std::memory_order_relaxed) != 0;
}

void requestInterrupt(int signal) {
  pendingSignal.store(signal, std::memory_order_relaxed);
}

int interruptSignal() {
  return pendingSignal.load(std::memory_order_relaxed);
}

void clearInterrupt() {
  pendingSignal.store(0, std::memory_order_relaxed);
}

}  // namespace radiant
