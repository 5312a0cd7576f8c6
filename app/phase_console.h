// The long phases (util/phase.h) on stderr: a bar with its ETA on a
// terminal, a line every few seconds in a log; a phase that took a second or
// more says so when it ends, shorter ones leave no trace.
#pragma once

#include "util/phase.h"

namespace radiant {

/// Listens to the phases while alive (when `enabled`: not --quiet, rank 0).
class ConsolePhases {
 public:
  explicit ConsolePhases(bool enabled);
  ~ConsolePhases();
  ConsolePhases(const ConsolePhases &) = delete;
  ConsolePhases &operator=(const ConsolePhases &) = delete;
};

}  // namespace radiant
