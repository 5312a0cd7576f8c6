// Where a run's time goes, for the engineers: with RADIANT_TIMING set in the
// environment, a ScopedTiming prints its label and the seconds from its
// construction to its destruction on stderr (`  label   1.234 s`). Without
// it, nothing is printed and the cost is one getenv per scope.
#pragma once

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

class ScopedTiming {
 public:
  explicit ScopedTiming(std::string label) : label_(std::move(label)), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTiming() {
    if (timingRequested())
      std::fprintf(stderr, "  %-28s %.3f s\n", label_.c_str(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }
  ScopedTiming(const ScopedTiming &) = delete;
  ScopedTiming &operator=(const ScopedTiming &) = delete;

 private:
  std::string label_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace radiant
