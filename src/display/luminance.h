// Photometry of linear RGB images: luminance in cd/m², the lambert, and the
// image statistics the tone operators adapt to.
//
// Radiant's images hold radiance in W·sr⁻¹·m⁻² per linear Rec.709/sRGB
// primary. Luminance is the Y row of the sRGB → XYZ matrix (IEC 61966-2-1)
// times the luminous efficacy K_m = 683 lm/W (CIE 015): a white of 1
// W·sr⁻¹·m⁻² in every channel is 683 cd/m².
#pragma once

#include <span>

#include "io/image.h"
#include "util/spectrum.h"

namespace radiant {

/// Y row of the linear sRGB → XYZ matrix (IEC 61966-2-1), D65 white Y = 1.
constexpr double kRec709LuminanceWeights[3] = {0.2126390, 0.7151687, 0.0721923};

/// Luminance-weighted radiance, W·sr⁻¹·m⁻² (no efficacy): the "Y" of an RGB triple.
inline double relativeLuminance(const double rgb[3]) {
  return kRec709LuminanceWeights[0] * rgb[0] + kRec709LuminanceWeights[1] * rgb[1] +
         kRec709LuminanceWeights[2] * rgb[2];
}
inline double relativeLuminance(const float rgb[3]) {
  const double d[3] = {rgb[0], rgb[1], rgb[2]};
  return relativeLuminance(d);
}

/// Luminance in cd/m² of linear RGB radiance in W·sr⁻¹·m⁻².
inline double luminanceCdPerM2(const float rgb[3]) {
  return kLuminousEfficacy * relativeLuminance(rgb);
}
inline double luminanceCdPerM2(const double rgb[3]) {
  return kLuminousEfficacy * relativeLuminance(rgb);
}

/// Tumblin & Rushmeier (IEEE CG&A 1993) work in lamberts: 1 L = 10⁴/π cd/m².
constexpr double kLambertsPerCdM2 = 3.14159265358979323846e-4;
constexpr double lambertsFromCdPerM2(double cdPerM2) {
  return cdPerM2 * kLambertsPerCdM2;
}
constexpr double cdPerM2FromLamberts(double lamberts) {
  return lamberts / kLambertsPerCdM2;
}

/// What the operators read from the whole image, computed once.
struct LuminanceStatistics {
  /// exp(mean ln L) over the pixels with finite L > 0, cd/m². Black pixels are
  /// left out: one would send the mean to −∞, and a small offset δ (as in
  /// Reinhard et al.) would make the result depend on the absolute level, which
  /// the scale-invariant operators must not. 0 if no pixel is lit.
  double logAverage = 0;
  double maximum = 0;  ///< largest finite luminance, cd/m²
  size_t litPixels = 0;
  size_t nonFinitePixels = 0;  ///< NaN or ±Inf in some channel
};

LuminanceStatistics luminanceStatistics(const Image &image);

/// The radiance scale that shows the image's log-average luminance at display
/// value `key` (0.18: middle grey). The log-average is in cd/m², the display
/// value in radiance units, hence the efficacy. Needs a lit image.
inline double keyExposureScale(const LuminanceStatistics &stats, double key) {
  return key * kLuminousEfficacy / stats.logAverage;
}

}  // namespace radiant
