// `tumblin-rushmeier` — tone reproduction (Tumblin & Rushmeier, "Tone
// reproduction for realistic images", IEEE CG&A 13(6), 1993; C&W §9.5): the
// display luminance whose perceived brightness, for an observer adapted to the
// display, equals the brightness a real-world observer adapted to the scene
// would perceive. Absolute luminance in, so a dim room looks dim and a bright
// one bright (the paper's eq. 13–15).
//
// Brightness (Stevens & Stevens, eq. 7, 9, 10), luminances in lamberts:
//   B = 10^β(L_a) · L^α(L_a),  α = 0.4 log10 L_a + 2.92,  β = −0.4 (log10 L_a)² − 2.584 log10 L_a + 2.0208
// Matching world and display observers (eq. 13):
//   L_d = L_w^(α_w/α_d) · 10^((β_w − β_d)/α_d)
// with the world adaptation L_wa from the image (eq. 11: log10 L_wa =
// E{log10 L} + 0.84) and the display adaptation L_w(d) = L_dmax/√C_max (eq. 14).
// The display model (eq. 12) L_d = L_dmax · n^γd + L_dmax/C_max then gives the
// frame-buffer value n = (L_d/L_dmax − 1/C_max)^(1/γd) (eq. 15): this operator
// outputs I/k = L_d/L_dmax − 1/C_max, and the transfer curve does the rest, so
// `--gamma G` makes it eq. 15 with γd = G exactly, and the default sRGB curve
// stands in for a γd ≈ 2.2 display. Colour is scaled by the luminance ratio.
//
// Parameters: --display-max L_dmax (86 cd/m²; also the display model's k),
// --display-contrast C_max (35), --adaptation L_wa (cd/m², default eq. 11).
// Every luminance is converted to lamberts before the power law and L_d back.
//
// Limits: the fit is flawed for very dim scenes, below S = 27 dB
// (L_wa < 10^-7.3 lambert ≈ 1.6·10⁻⁴ cd/m²), where α turns negative; a
// warning says so.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "display/tone_operator.h"

namespace radiant {

namespace {

double alpha(double adaptationLamberts) {
  return 0.4 * std::log10(adaptationLamberts) + 2.92;
}
double beta(double adaptationLamberts) {
  double x = std::log10(adaptationLamberts);
  return -0.4 * x * x - 2.584 * x + 2.0208;
}

/// L_d = L_w^exponent · factor, in lamberts, for one pair of adaptation levels.
struct BrightnessMatch {
  double exponent = 1, factor = 1;
  BrightnessMatch(double worldAdaptationCdM2, double displayAdaptationCdM2) {
    double wa = lambertsFromCdPerM2(worldAdaptationCdM2), da = lambertsFromCdPerM2(displayAdaptationCdM2);
    exponent = alpha(wa) / alpha(da);
    factor = std::pow(10.0, (beta(wa) - beta(da)) / alpha(da));
  }
  double displayCdM2(double worldCdM2) const {
    if (!(worldCdM2 > 0)) return 0;
    return cdPerM2FromLamberts(std::pow(lambertsFromCdPerM2(worldCdM2), exponent) * factor);
  }
};

class TumblinRushmeierOperator final : public ToneOperator {
 public:
  TumblinRushmeierOperator(double worldAdaptation, double displayMax, double contrast, std::string description)
      : match_(worldAdaptation, displayMax / std::sqrt(contrast)),
        displayMax_(displayMax),
        contrast_(contrast),
        description_(std::move(description)) {}
  void map(const float radiance[3], double display[3]) const override {
    double displayLuminance = match_.displayCdM2(luminanceCdPerM2(radiance));
    scaleToLuminance(radiance, std::max(0.0, displayLuminance / displayMax_ - 1 / contrast_), display);
  }
  std::string describe() const override { return description_; }

 private:
  BrightnessMatch match_;
  double displayMax_, contrast_;
  std::string description_;
};

}  // namespace

double tumblinRushmeierDisplayLuminance(double worldCdM2, double worldAdaptationCdM2, double displayMaxCdM2,
                                        double displayContrast) {
  return BrightnessMatch(worldAdaptationCdM2, displayMaxCdM2 / std::sqrt(displayContrast)).displayCdM2(worldCdM2);
}

double tumblinRushmeierAdaptation(double logAverageCdM2) {
  return logAverageCdM2 * std::pow(10.0, 0.84);
}

std::unique_ptr<ToneOperator> createTumblinRushmeierOperator(const Image &radiance, const ToneParameters &p,
                                                             ToneWarnings &warnings) {
  const double displayMax = p.displayMaxCdM2.value_or(kTumblinRushmeierDisplayMaxCdM2);
  double adaptation = 0;
  std::string origin;
  if (p.adaptationCdM2) {
    adaptation = *p.adaptationCdM2;
    origin = "given";
  } else {
    LuminanceStatistics stats = luminanceStatistics(radiance);
    adaptation = tumblinRushmeierAdaptation(stats.logAverage);
    origin = fmt::format("log-average {:.4g} cd/m² × 10^0.84, eq. 11", stats.logAverage);
    if (stats.litPixels == 0) {
      warnings.push_back("tumblin-rushmeier: the image is black");
      adaptation = displayMax / std::sqrt(p.displayContrast);  // the identity mapping; nothing to show anyway
      origin = "black image";
    }
  }
  if (lambertsFromCdPerM2(adaptation) < std::pow(10.0, -7.3))
    warnings.push_back(fmt::format(
        "tumblin-rushmeier: world adaptation {:.3g} cd/m² is below 27 dB (1.6e-4 cd/m²), where the brightness model "
        "fails (Tumblin & Rushmeier 1993); the image is not meaningful",
        adaptation));
  return std::make_unique<TumblinRushmeierOperator>(
      adaptation, displayMax, p.displayContrast,
      fmt::format("tumblin-rushmeier: world adaptation {:.4g} cd/m² ({}), display {:.4g} cd/m² maximum, contrast "
                  "{:.3g}, display adaptation {:.4g} cd/m²",
                  adaptation, origin, displayMax, p.displayContrast, displayMax / std::sqrt(p.displayContrast)));
}

}  // namespace radiant
