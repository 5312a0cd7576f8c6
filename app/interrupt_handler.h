// SIGINT/SIGTERM for the long commands (render, solve): the first signal asks
// the running work to stop (util/interrupt.h) and says so on stderr; a second
// one ends the program at once, as if no handler were installed.
#pragma once

namespace radiant {

/// Installs the handlers for its lifetime; the previous ones come back after.
class InterruptHandler {
 public:
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler &) = delete;
  InterruptHandler &operator=(const InterruptHandler &) = delete;
};

/// The exit status of a run that an interrupt ended: 128 + the signal (130 for Ctrl-C).
int interruptedExitStatus();

}  // namespace radiant
