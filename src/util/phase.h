// Progress of the long phases before a solve or an image: loading, the BVH,
// cutting faces, meshing. A phase announces itself (Phase) and, where it
// knows its amount of work, how much is done; whoever listens (the command
// line: a bar with an ETA on a terminal, a line every few seconds in a log)
// hears at most a few events a second, and one at the end. Nobody listens
// by default (tests, benchmarks, `--quiet`).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace radiant {

struct PhaseEvent {
  std::string name;      ///< "cutting faces", …
  double fraction = -1;  ///< of the phase's work done; < 0 when the phase cannot tell
  double elapsedSeconds = 0;
  double etaSeconds = -1;  ///< < 0 when unknown
  bool done = false;       ///< the last event of the phase
};
using PhaseListener = std::function<void(const PhaseEvent &)>;

/// The listener of every phase from now on (empty: none). Not thread-safe: set it before the work starts.
void setPhaseListener(PhaseListener listener);

/// One phase, from construction to destruction. advance() may be called from any thread.
class Phase {
 public:
  explicit Phase(std::string name, size_t totalWork = 0);
  ~Phase();
  Phase(const Phase &) = delete;
  Phase &operator=(const Phase &) = delete;
  /// `work` more units of the total done.
  void advance(size_t work = 1);

 private:
  void report(bool done);
  std::string name_;
  size_t total_;
  std::atomic<size_t> done_{0};
  std::chrono::steady_clock::time_point start_, lastReport_;
  std::mutex reporting_;
};

}  // namespace radiant
