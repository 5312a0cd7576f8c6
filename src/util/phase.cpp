#include "util/phase.h"

namespace radiant {

namespace {

PhaseListener &listener() {
  static PhaseListener instance;
  return instance;
}

double secondsBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

void setPhaseListener(PhaseListener l) {
  listener() = std::move(l);
}

Phase::Phase(std::string name, size_t totalWork)
    : name_(std::move(name)), total_(totalWork), start_(std::chrono::steady_clock::now()), lastReport_(start_) {
  if (listener()) report(false);
}

Phase::~Phase() {
  if (listener()) report(true);
}

void Phase::advance(size_t work) {
  const size_t before = done_.fetch_add(work);
  // The clock only each 1024 units of work: advance() is called per face.
  if (!listener() || (before >> 10) == ((before + work) >> 10)) return;
  // At most five events a second, from whichever thread comes first.
  std::unique_lock lock(reporting_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  const auto now = std::chrono::steady_clock::now();
  if (secondsBetween(lastReport_, now) < 0.2) return;
  lastReport_ = now;
  lock.unlock();
  report(false);
}

void Phase::report(bool done) {
  PhaseEvent event;
  event.name = name_;
  event.elapsedSeconds = secondsBetween(start_, std::chrono::steady_clock::now());
  event.done = done;
  if (done) {
    event.fraction = 1, event.etaSeconds = 0;
  } else if (total_ > 0) {
    event.fraction = std::min(1.0, double(done_.load()) / double(total_));
    if (event.fraction > 0) event.etaSeconds = event.elapsedSeconds * (1 - event.fraction) / event.fraction;
  }
  std::lock_guard lock(reporting_);
  listener()(event);
}

}  // namespace radiant
