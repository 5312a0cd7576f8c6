// `reinhard` — the global operator of Reinhard, Stark, Shirley & Ferwerda,
// "Photographic tone reproduction for digital images", SIGGRAPH 2002, §3.1:
//
//   L = (a / L̄_w) · L_w                     (eq. 2; L̄_w the log-average luminance, a the key)
//   L_d = L (1 + L / L_white²) / (1 + L)    (eq. 4; without a white point L / (1 + L), eq. 3)
//
// L_d is the display luminance as a fraction of full scale; colour is scaled by
// L_d/L_w. Like every key-based operator it normalises the absolute level away.
//
// Parameters: --key a (default 0.18, "middle grey"), --white L_white in cd/m²
// (world luminance that maps to full white; default none: eq. 3, which never
// quite reaches white). L̄_w leaves black pixels out (display/luminance.h)
// instead of adding the paper's small δ, which would depend on the units.
#include <fmt/format.h>

#include "display/tone_operator.h"

namespace radiant {

namespace {

class ReinhardOperator final : public ToneOperator {
 public:
  ReinhardOperator(double scale, std::optional<double> scaledWhite, std::string description)
      : scale_(scale), scaledWhite_(scaledWhite), description_(std::move(description)) {}
  void map(const float radiance[3], double display[3]) const override {
    scaleToLuminance(radiance, reinhardCurve(scale_ * luminanceCdPerM2(radiance), scaledWhite_), display);
  }
  std::string describe() const override { return description_; }

 private:
  double scale_;  ///< a / L̄_w, per cd/m²
  std::optional<double> scaledWhite_;
  std::string description_;
};

}  // namespace

double reinhardCurve(double scaledLuminance, std::optional<double> scaledWhite) {
  const double l = scaledLuminance;
  if (!(l > 0)) return 0;
  if (!scaledWhite) return l / (1 + l);
  return l * (1 + l / (*scaledWhite * *scaledWhite)) / (1 + l);
}

std::unique_ptr<ToneOperator> createReinhardOperator(const Image &radiance, const ToneParameters &p,
                                                     ToneWarnings &warnings) {
  LuminanceStatistics stats = luminanceStatistics(radiance);
  if (stats.litPixels == 0) {
    warnings.push_back("reinhard: the image is black");
    return std::make_unique<ReinhardOperator>(0.0, std::nullopt, "reinhard: black image");
  }
  const double scale = p.key / stats.logAverage;
  std::optional<double> white;
  if (p.whiteCdM2) white = *p.whiteCdM2 * scale;
  return std::make_unique<ReinhardOperator>(
      scale, white,
      fmt::format("reinhard: key {:.3g}, log-average {:.4g} cd/m², {}", p.key, stats.logAverage,
                  p.whiteCdM2 ? fmt::format("white {:.4g} cd/m²", *p.whiteCdM2) : std::string("no white point")));
}

}  // namespace radiant
