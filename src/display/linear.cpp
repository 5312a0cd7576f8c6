// `linear` — the display value is the radiance times an exposure:
// I/k = 2^stops · L (each channel, W·sr⁻¹·m⁻²). With the default 0 stops a
// radiance of 1 W·sr⁻¹·m⁻² is full white, which is what render's PNG has always
// shown: `--exposure S` alone is `--tonemap linear --exposure S`.
//
// Parameters: --exposure STOPS (default 0, or the scene's render.exposure in
// render), or --exposure auto: the exposure that shows the image's log-average
// luminance (display/luminance.h) at the display value --key (default 0.18,
// "middle grey"). Auto exposure makes the image independent of the absolute
// level: the normalised linear mapping of C&W §9.5, which shows a dim and a
// bright room alike (Tumblin & Rushmeier 1993's firefly and searchlight).
#include <fmt/format.h>

#include <cmath>

#include "display/tone_operator.h"

namespace radiant {

namespace {

class LinearOperator final : public ToneOperator {
 public:
  LinearOperator(double scale, std::string description) : scale_(scale), description_(std::move(description)) {}
  void map(const float radiance[3], double display[3]) const override {
    for (int c = 0; c < 3; ++c) display[c] = radiance[c] * scale_;
  }
  std::string describe() const override { return description_; }

 private:
  double scale_;
  std::string description_;
};

}  // namespace

std::unique_ptr<ToneOperator> createScaleOperator(double scale, std::string description) {
  return std::make_unique<LinearOperator>(scale, std::move(description));
}

std::unique_ptr<ToneOperator> createLinearOperator(const Image &radiance, const ToneParameters &p,
                                                   ToneWarnings &warnings) {
  if (!p.autoExposure)
    return std::make_unique<LinearOperator>(std::exp2(p.exposureStops),
                                            fmt::format("linear: exposure {:+.3g} stops", p.exposureStops));
  LuminanceStatistics stats = luminanceStatistics(radiance);
  if (stats.litPixels == 0) {
    warnings.push_back("linear --exposure auto: the image is black; exposure 0 stops");
    return std::make_unique<LinearOperator>(1.0, "linear: exposure auto (black image), 0 stops");
  }
  const double scale = keyExposureScale(stats, p.key);
  return std::make_unique<LinearOperator>(
      scale, fmt::format("linear: exposure auto {:+.3g} stops (log-average {:.4g} cd/m² shown at {:.3g})",
                         std::log2(scale), stats.logAverage, p.key));
}

}  // namespace radiant
