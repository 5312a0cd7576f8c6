#include "interrupt_handler.h"

#include <signal.h>
#include <unistd.h>

#include <cstring>

#include "util/interrupt.h"

namespace radiant {

namespace {

struct sigaction previousInt, previousTerm;

void onSignal(int signal) {
  if (interruptRequested()) {
    // The second Ctrl-C: the default action (terminate), now.
    ::signal(signal, SIG_DFL);
    ::raise(signal);
    return;
  }
  requestInterrupt(signal);
  // write(2) is async-signal-safe; fmt and stdio are not.
  static const char message[] =
      "\nradiant: interrupted: stopping at the next safe point (press Ctrl-C again to quit at once)\n";
  ssize_t ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
  (void)ignored;
}

}  // namespace

InterruptHandler::InterruptHandler() {
  clearInterrupt();
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &previousInt);
  sigaction(SIGTERM, &action, &previousTerm);
}

InterruptHandler::~InterruptHandler() {
  sigaction(SIGINT, &previousInt, nullptr);
  sigaction(SIGTERM, &previousTerm, nullptr);
}

int interruptedExitStatus() {
  const int signal = interruptSignal();
  return 128 + (signal > 0 ? signal : SIGINT);
}

}  // namespace radiant
