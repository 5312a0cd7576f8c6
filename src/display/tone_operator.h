// Tone operators: from linear radiance (W·sr⁻¹·m⁻², linear Rec.709 RGB) to
// display-linear values, the fraction I/k of the display's maximum that each
// channel should emit (C&W §9.5; docs/tone-mapping.md).
//
// One operator per file (linear.cpp, max_reflected.cpp, tumblin_rushmeier.cpp,
// ward.cpp, reinhard.cpp, aces.cpp), one table of them (tone_registry.cpp).
// An operator is built for one image: its constructor reads what it adapts to
// (log-average luminance, brightest reflecting pixel) and `map` is then a pure
// per-pixel function. What follows it — the out-of-gamut rule, the transfer
// curve (sRGB or gamma) and quantisation — is display_mapping.h.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "display/luminance.h"
#include "io/image.h"
#include "util/parameters.h"

namespace radiant {

/// Every operator's parameters, as the command line gives them (docs/cli.md).
/// An operator reads only its own; the registry lists which those are.
struct ToneParameters {
  double exposureStops = 0;              ///< linear: radiance × 2^stops is the display value
  bool autoExposure = false;             ///< linear: choose the exposure so the log-average luminance shows as `key`
  double key = 0.18;                     ///< linear (auto), reinhard, aces: display value of the log-average luminance
  double reflectedLevel = 0.95;          ///< max-reflected: display value of the brightest reflecting pixel
  std::optional<double> displayMaxCdM2;  ///< tumblin-rushmeier (86), ward (100): L_dmax = k, cd/m²
  double displayContrast = 35;           ///< tumblin-rushmeier: C_max, the display's contrast ratio
  std::optional<double> adaptationCdM2;  ///< tumblin-rushmeier, ward: world adaptation luminance, cd/m²
  std::optional<double> whiteCdM2;       ///< reinhard: world luminance that maps to full white, cd/m²
};

class ToneOperator {
 public:
  virtual ~ToneOperator() = default;
  /// Display-linear RGB for one pixel's radiance: the fraction of the display's
  /// maximum per channel (may exceed 1; the gamut rule handles that).
  virtual void map(const float radiance[3], double display[3]) const = 0;
  /// One line for the log: the constants taken from the image.
  virtual std::string describe() const = 0;
};

/// Warnings an operator raises while it adapts to the image, for the user.
using ToneWarnings = std::vector<std::string>;

struct ToneOperatorInfo {
  const char *name;
  const char *summary;
  std::unique_ptr<ToneOperator> (*create)(const Image &radiance, const ToneParameters &, ToneWarnings &);
  /// Its parameters (util/parameters.h): the ToneParameters fields it reads,
  /// with their defaults, ranges and meaning (the command line's --exposure, --key, …).
  ParameterTable parameters;
};

/// ToneParameters from the given values, checked against the operator's
/// table (a parameter it does not declare is an InputError naming the
/// operators that do). `defaultExposureStops`: linear's exposure when none is
/// given (render: the scene's render.exposure).
ToneParameters toneParameters(const ToneOperatorInfo &op, const ParameterValues &given, double defaultExposureStops);

const std::vector<ToneOperatorInfo> &toneOperatorRegistry();
/// The entry for `name`; throws InputError at --tonemap listing the known names.
const ToneOperatorInfo &findToneOperator(const std::string &name);

/// Display = radiance × scale, the same for every channel (linear.cpp; max-reflected uses it too).
std::unique_ptr<ToneOperator> createScaleOperator(double scale, std::string description);
std::unique_ptr<ToneOperator> createLinearOperator(const Image &, const ToneParameters &, ToneWarnings &);
std::unique_ptr<ToneOperator> createMaxReflectedOperator(const Image &, const ToneParameters &, ToneWarnings &);
std::unique_ptr<ToneOperator> createTumblinRushmeierOperator(const Image &, const ToneParameters &, ToneWarnings &);
std::unique_ptr<ToneOperator> createWardOperator(const Image &, const ToneParameters &, ToneWarnings &);
std::unique_ptr<ToneOperator> createReinhardOperator(const Image &, const ToneParameters &, ToneWarnings &);
std::unique_ptr<ToneOperator> createAcesOperator(const Image &, const ToneParameters &, ToneWarnings &);

/// Colour at a new luminance: rgb · (displayLuminance / Y(rgb)). Keeps the
/// chromaticity (hue and saturation); black or negative luminance gives black.
void scaleToLuminance(const float radiance[3], double displayLuminance, double display[3]);

// ---- The curves themselves, exposed for the tests (Tumblin & Rushmeier 1993; Ward, Graphics Gems IV) ----

constexpr double kTumblinRushmeierDisplayMaxCdM2 = 86;
constexpr double kWardDisplayMaxCdM2 = 100;

/// Tumblin & Rushmeier 1993 eq. 13: the display luminance L_d (cd/m²) whose
/// perceived brightness on a display adapted to L_w(d) = L_dmax/√C_max (eq. 14)
/// matches that of world luminance L_w seen adapted to L_wa. Every luminance is
/// converted to lamberts for the power law, and L_d back to cd/m².
double tumblinRushmeierDisplayLuminance(double worldCdM2, double worldAdaptationCdM2, double displayMaxCdM2,
                                        double displayContrast);
/// Eq. 11: log10 L_wa = E{log10 L} + 0.84, L_wa in cd/m² from the image's log-average.
double tumblinRushmeierAdaptation(double logAverageCdM2);
/// Ward 1994: m = [(1.219 + L_da^0.4) / (1.219 + L_wa^0.4)]^2.5 with L_da = L_dmax/2, cd/m².
double wardScaleFactor(double worldAdaptationCdM2, double displayMaxCdM2);
/// Reinhard et al. 2002 eq. 4 on scaled luminance L: L(1 + L/L_white²)/(1 + L); without a white point L/(1 + L).
double reinhardCurve(double scaledLuminance, std::optional<double> scaledWhite);
/// Hill's fit of the ACES RRT + sRGB ODT: linear sRGB in (0.18 = mid grey), display-linear sRGB out, [0,1].
void acesFitted(const double in[3], double out[3]);

}  // namespace radiant
