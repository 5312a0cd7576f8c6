// `ward` — Ward's contrast-based scale factor (G. Ward, "A contrast-based
// scalefactor for luminance display", Graphics Gems IV, 1994, pp. 415–421).
// One linear scale m, chosen so that a just-noticeable luminance difference
// at the world adaptation level (Blackwell's threshold model) maps to a
// just-noticeable difference on the display:
//
//   m = [ (1.219 + L_da^0.4) / (1.219 + L_wa^0.4) ]^2.5,  L_da = L_dmax / 2
//   L_d = m · L_w,   I/k = L_d / L_dmax
//
// Luminances in cd/m². Being one scale, it keeps colours as they are, and a dim
// scene stays dim: m is at most (1 + L_da^0.4/1.219)^2.5 times brighter.
//
// Parameters: --display-max L_dmax (100 cd/m²; also the display model's k),
// --adaptation L_wa (cd/m², default the image's log-average luminance).
#include <fmt/format.h>

#include <cmath>

#include "display/tone_operator.h"

namespace radiant {

namespace {

class WardOperator final : public ToneOperator {
 public:
  WardOperator(double scale, std::string description) : scale_(scale), description_(std::move(description)) {}
  void map(const float radiance[3], double display[3]) const override {
    for (int c = 0; c < 3; ++c) display[c] = radiance[c] * scale_;
  }
  std::string describe() const override { return description_; }

 private:
  double scale_;  ///< radiance → I/k: 683 · m / L_dmax
  std::string description_;
};

}  // namespace

double wardScaleFactor(double worldAdaptationCdM2, double displayMaxCdM2) {
  return std::pow((1.219 + std::pow(displayMaxCdM2 / 2, 0.4)) / (1.219 + std::pow(worldAdaptationCdM2, 0.4)), 2.5);
}

std::unique_ptr<ToneOperator> createWardOperator(const Image &radiance, const ToneParameters &p,
                                                 ToneWarnings &warnings) {
  const double displayMax = p.displayMaxCdM2.value_or(kWardDisplayMaxCdM2);
  double adaptation = 0;
  std::string origin = "given";
  if (p.adaptationCdM2) {
    adaptation = *p.adaptationCdM2;
  } else {
    LuminanceStatistics stats = luminanceStatistics(radiance);
    adaptation = stats.logAverage;
    origin = "log-average";
    if (stats.litPixels == 0) warnings.push_back("ward: the image is black");
  }
  const double m = wardScaleFactor(adaptation, displayMax);
  return std::make_unique<WardOperator>(
      kLuminousEfficacy * m / displayMax,
      fmt::format("ward: world adaptation {:.4g} cd/m² ({}), display {:.4g} cd/m² maximum, scale factor m = {:.4g}",
                  adaptation, origin, displayMax, m));
}

}  // namespace radiant
