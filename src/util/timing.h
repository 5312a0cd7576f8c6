// Where a run's time goes, for the engineers: with RADIANT_TIMING set in the
// environment, a ScopedTiming prints its label and the seconds from its
// construction to its destruction on stderr, and the CPU time of the whole
// process over the same span (`  label   1.234 s (cpu 2.345 s)`): under
// mpirun, where ranks share cores and wait for each other, the CPU time says
// what a phase cost. Without it, nothing is printed and the cost is one
// getenv per scope.
#pragma once

#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace radiant {

/// Whether RADIANT_TIMING is set (read once).
inline bool timingRequested() {
  static const bool requested = std::getenv("RADIANT_TIMING") != nullptr;
  return requested;
}

/// The seconds since a start, on the clock and of the process's CPU.
class TimingClock {
 public:
  TimingClock() : start_(std::chrono::steady_clock::now()), startCpu_(processCpuSeconds()) {}
  /// Prints `label`, the seconds since the start and the CPU seconds, then starts again.
  void print(const char *label) {
    const auto now = std::chrono::steady_clock::now();
    const double cpu = processCpuSeconds();
    std::fprintf(stderr, "  %-28s %.3f s (cpu %.3f s)\n", label, std::chrono::duration<double>(now - start_).count(),
                 cpu - startCpu_);
    start_ = now, startCpu_ = cpu;
  }

 private:
  std::chrono::steady_clock::time_point start_;
  double startCpu_;

  static double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
};

/// Prints its label and times at the end of its scope, under RADIANT_TIMING.
class ScopedTiming {
 public:
  explicit ScopedTiming(std::string label) : label_(std::move(label)) {}
  ~ScopedTiming() {
    if (timingRequested()) clock_.print(label_.c_str());
  }
  ScopedTiming(const ScopedTiming &) = delete;
  ScopedTiming &operator=(const ScopedTiming &) = delete;

 private:
  std::string label_;
  TimingClock clock_;
};

/// Consecutive phases of one scope: each lap prints, under RADIANT_TIMING,
/// the time since the previous lap (or the construction).
class TimingLaps {
 public:
  void lap(const char *label) {
    if (timingRequested()) clock_.print(label);
  }

 private:
  TimingClock clock_;
};

}  // namespace radiant
