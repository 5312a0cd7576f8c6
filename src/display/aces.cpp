// `aces` — a filmic curve: Stephen Hill's fit of the ACES reference rendering
// transform plus the sRGB output transform (RRT + ODT), as published in his
// BakingLab (MIT licence, file ACES.hlsl, 2016):
//
//   v = M_in · c;   v' = (v (v + 0.0245786) − 0.000090537) / (v (0.983729 v + 0.4329510) + 0.238081);   out = M_out ·
//   v'
//
// M_in takes linear sRGB into the RRT's working space (sRGB → XYZ → D65→D60 →
// AP1, with the RRT's desaturation), M_out back (ODT desaturation, AP1 → XYZ →
// D60→D65 → sRGB). Unlike the luminance operators it works per channel, so
// bright saturated colours shift towards white as film does; the result is
// clamped to [0, 1]. It is closer to the real RRT+ODT than Narkowicz's 2015
// one-line fit (x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)), which ignores
// the colour matrices.
//
// Scene-referred input: the image is first exposed so that its log-average
// luminance sits at --key (default 0.18); 0.18 then maps to display-linear
// 0.106 (sRGB 92/255), ACES's darker middle grey.
#include <fmt/format.h>

#include <algorithm>

#include "display/tone_operator.h"

namespace radiant {

namespace {

constexpr double kAcesInput[3][3] = {
    {0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
constexpr double kAcesOutput[3][3] = {
    {1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};

class AcesOperator final : public ToneOperator {
 public:
  AcesOperator(double exposure, std::string description) : exposure_(exposure), description_(std::move(description)) {}
  void map(const float radiance[3], double display[3]) const override {
    const double exposed[3] = {radiance[0] * exposure_, radiance[1] * exposure_, radiance[2] * exposure_};
    acesFitted(exposed, display);
  }
  std::string describe() const override { return description_; }

 private:
  double exposure_;
  std::string description_;
};

}  // namespace

void acesFitted(const double in[3], double out[3]) {
  double fitted[3];
  for (int r = 0; r < 3; ++r) {
    double v = kAcesInput[r][0] * in[0] + kAcesInput[r][1] * in[1] + kAcesInput[r][2] * in[2];
    fitted[r] = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
  }
  for (int r = 0; r < 3; ++r)
    out[r] = std::clamp(kAcesOutput[r][0] * fitted[0] + kAcesOutput[r][1] * fitted[1] + kAcesOutput[r][2] * fitted[2],
                        0.0, 1.0);
}

std::unique_ptr<ToneOperator> createAcesOperator(const Image &radiance, const ToneParameters &p,
                                                 ToneWarnings &warnings) {
  LuminanceStatistics stats = luminanceStatistics(radiance);
  if (stats.litPixels == 0) {
    warnings.push_back("aces: the image is black");
    return std::make_unique<AcesOperator>(1.0, "aces: black image");
  }
  // The log-average is in cd/m²; the curve takes radiance-like values where 0.18 is middle grey.
  const double exposure = keyExposureScale(stats, p.key);
  return std::make_unique<AcesOperator>(
      exposure,
      fmt::format("aces (Hill's RRT+ODT fit): log-average {:.4g} cd/m² exposed to {:.3g}", stats.logAverage, p.key));
}

}  // namespace radiant
