// The table of tone operators: name → factory and the flags of its parameters,
// one line per operator.
#include <fmt/format.h>

#include "display/tone_operator.h"
#include "util/error.h"

namespace radiant {

const std::vector<ToneOperatorInfo> &toneOperatorRegistry() {
  static const std::vector<ToneOperatorInfo> table = {
      {"linear",
       "radiance × 2^exposure (--exposure STOPS, or auto: log-average shown at --key)",
       &createLinearOperator,
       {"--exposure", "--key"}},
      {"max-reflected",
       "brightest non-emitting pixel at --reflected-level (0.95), lights clamp",
       &createMaxReflectedOperator,
       {"--reflected-level"}},
      {"tumblin-rushmeier",
       "Tumblin & Rushmeier 1993 brightness-matching tone reproduction (absolute)",
       &createTumblinRushmeierOperator,
       {"--display-max", "--display-contrast", "--adaptation"}},
      {"ward",
       "Ward 1994 contrast-based scale factor (absolute)",
       &createWardOperator,
       {"--display-max", "--adaptation"}},
      {"reinhard",
       "Reinhard et al. 2002 global operator (--key, --white)",
       &createReinhardOperator,
       {"--key", "--white"}},
      {"aces", "Hill's fit of the ACES filmic RRT+ODT, exposed by --key", &createAcesOperator, {"--key"}},
  };
  return table;
}

const ToneOperatorInfo &findToneOperator(const std::string &name) {
  std::string names;
  for (const ToneOperatorInfo &info : toneOperatorRegistry()) {
    if (name == info.name) return info;
    names += names.empty() ? info.name : std::string(", ") + info.name;
  }
  throw InputError(InputLocation::ofParameter("tonemap"),
                   fmt::format("unknown tone operator '{}'; known: {}", name, names));
}

void scaleToLuminance(const float radiance[3], double displayLuminance, double display[3]) {
  const double luminance = relativeLuminance(radiance);
  const double ratio = luminance > 0 && displayLuminance > 0 ? displayLuminance / luminance : 0.0;
  for (int c = 0; c < 3; ++c) display[c] = radiance[c] * ratio;
}

}  // namespace radiant
