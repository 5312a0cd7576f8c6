// Ctrl-C during a long run. The command line's SIGINT/SIGTERM handler asks
// (requestInterrupt); the loops that can stop with something useful answer:
// the render driver finishes the tiles in flight and returns the image so far,
// a solver's progress callback throws Interrupted so that nothing partial is
// written. Everything else runs on to its next check.
#pragma once

#include <stdexcept>

namespace radiant {

/// True once an interrupt was asked for (async-signal-safe to set).
bool interruptRequested();
/// Asks for an interrupt; `signal` is the signal's number, for the exit code (128 + signal).
void requestInterrupt(int signal = 2);
/// The signal of the pending interrupt, or 0.
int interruptSignal();
/// Forgets a pending interrupt (tests; a command that has handled it).
void clearInterrupt();

/// Thrown where work stops at an interrupt and nothing of it is kept.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace radiant
