// The table of tone operators: name → factory and its parameter table, one
// entry per operator.
#include <fmt/format.h>

#include <limits>

#include "display/tone_operator.h"
#include "util/error.h"
#include "util/parameters.h"

namespace radiant {

namespace {

// Parameters several operators share are declared once.
ParameterSpec key() {
  return {"key", ParameterType::Real, "0.18",
          "display value of the log-average luminance (linear: only with exposure auto)", kPositive};
}
ParameterSpec displayMax() {
  return {"display-max",
          ParameterType::Real,
          "",
          "the display's maximum luminance L_dmax in cd/m² (k of the display model)",
          kPositive,
          std::numeric_limits<double>::infinity(),
          {},
          "86 (tumblin-rushmeier), 100 (ward)"};
}
ParameterSpec adaptation() {
  return {"adaptation",
          ParameterType::Real,
          "",
          "the world adaptation luminance, cd/m² (tumblin-rushmeier: eq. 11, log-average × 10^0.84; ward: the "
          "log-average)",
          kPositive,
          std::numeric_limits<double>::infinity(),
          {},
          "from the image"};
}

}  // namespace

const std::vector<ToneOperatorInfo> &toneOperatorRegistry() {
  static const std::vector<ToneOperatorInfo> table = {
      {"linear",
       "radiance × 2^exposure (exposure in stops, or auto: the log-average luminance shown at key)",
       &createLinearOperator,
       {{"exposure",
         ParameterType::Real,
         "0",
         "radiance × 2^STOPS before the transfer curve, or auto: the exposure that shows the log-average luminance "
         "at key",
         -std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::infinity(),
         {"auto"},
         "the scene's render.exposure, else 0"},
        key()}},
      {"max-reflected",
       "brightest non-emitting pixel at reflected-level (0.95), lights clamp",
       &createMaxReflectedOperator,
       {{"reflected-level", ParameterType::Real, "0.95",
         "the display value of the brightest pixel that shows no "
         "emitter",
         1e-6, 1}}},
      {"tumblin-rushmeier",
       "Tumblin & Rushmeier 1993 brightness-matching tone reproduction (absolute)",
       &createTumblinRushmeierOperator,
       {displayMax(),
        {"display-contrast", ParameterType::Real, "35", "the display's contrast ratio C_max", 1.000001, 1e9},
        adaptation()}},
      {"ward", "Ward 1994 contrast-based scale factor (absolute)", &createWardOperator, {displayMax(), adaptation()}},
      {"reinhard",
       "Reinhard et al. 2002 global operator (key, white)",
       &createReinhardOperator,
       {key(),
        {"white",
         ParameterType::Real,
         "",
         "the world luminance shown as full white, cd/m²",
         kPositive,
         std::numeric_limits<double>::infinity(),
         {},
         "none"}}},
      {"aces", "Hill's fit of the ACES filmic RRT+ODT, exposed by key", &createAcesOperator, {key()}},
  };
  return table;
}

ToneParameters toneParameters(const ToneOperatorInfo &op, const ParameterValues &given, double defaultExposureStops) {
  std::vector<std::pair<std::string, const ParameterTable *>> others;
  for (const ToneOperatorInfo &info : toneOperatorRegistry()) others.push_back({info.name, &info.parameters});
  checkParameters(op.parameters, given, fmt::format("tone operator {}", op.name), others);
  const Parameters p(op.parameters, given);
  auto declares = [&](const char *name) {
    for (const ParameterSpec &spec : op.parameters)
      if (spec.name == name) return true;
    return false;
  };
  ToneParameters t;
  t.exposureStops = defaultExposureStops;
  if (declares("exposure") && p.given("exposure")) {
    if (p.text("exposure") == "auto")
      t.autoExposure = true;
    else
      t.exposureStops = p.real("exposure");
  }
  if (declares("key")) {
    t.key = p.real("key");
    if (op.name == std::string("linear") && p.given("key") && !t.autoExposure)
      throw InputError(p.origin("key"), "linear uses it only with exposure auto");
  }
  if (declares("reflected-level")) t.reflectedLevel = p.real("reflected-level");
  if (declares("display-contrast")) t.displayContrast = p.real("display-contrast");
  if (declares("display-max") && p.given("display-max")) t.displayMaxCdM2 = p.real("display-max");
  if (declares("adaptation") && p.given("adaptation")) t.adaptationCdM2 = p.real("adaptation");
  if (declares("white") && p.given("white")) t.whiteCdM2 = p.real("white");
  return t;
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
