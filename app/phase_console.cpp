#include "phase_console.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>

namespace radiant {

namespace {

constexpr double kWorthSaying = 1.0;  ///< seconds: a phase shorter than this is not reported

PhaseListener consoleListener() {
  const bool terminal = isatty(fileno(stderr));
  auto lastLine = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  auto shown = std::make_shared<bool>(false);  // a terminal line is on screen
  return [terminal, lastLine, shown](const PhaseEvent &e) {
    const std::string eta = e.etaSeconds >= 0 ? fmt::format("{:.1f}s", e.etaSeconds) : std::string("?");
    if (e.done) {
      if (e.elapsedSeconds >= kWorthSaying || *shown)
        fmt::print(stderr, "{}radiant: {}: {:.1f} s{}\n", terminal ? "\r" : "", e.name, e.elapsedSeconds,
                   terminal ? "                              " : "");
      *shown = false;
      return;
    }
    if (e.elapsedSeconds < kWorthSaying) return;
    if (terminal) {
      if (e.fraction >= 0) {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(e.fraction * kWidth + 0.5);
        fmt::print(stderr, "\r{} [{}{}] {:3.0f}%  {:.1f}s  ETA {}   ", e.name, std::string(filled, '#'),
                   std::string(kWidth - filled, '.'), 100 * e.fraction, e.elapsedSeconds, eta);
      } else {
        fmt::print(stderr, "\r{}… {:.1f}s   ", e.name, e.elapsedSeconds);
      }
      *shown = true;
    } else if (std::chrono::duration<double>(std::chrono::steady_clock::now() - *lastLine).count() >= 5) {
      *lastLine = std::chrono::steady_clock::now();
      if (e.fraction >= 0)
        fmt::print(stderr, "radiant: {}: {:.0f}% ({:.1f}s elapsed, ETA {})\n", e.name, 100 * e.fraction,
                   e.elapsedSeconds, eta);
      else
        fmt::print(stderr, "radiant: {}: {:.1f}s elapsed\n", e.name, e.elapsedSeconds);
    }
  };
}

}  // namespace

ConsolePhases::ConsolePhases(bool enabled) {
  if (enabled) setPhaseListener(consoleListener());
}

ConsolePhases::~ConsolePhases() {
  setPhaseListener({});
}

}  // namespace radiant
