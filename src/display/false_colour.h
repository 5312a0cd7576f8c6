// False-colour images of luminance (cd/m²) or illuminance (lux), with a scale
// bar, as lighting designers read them (docs/tone-mapping.md#false-colour).
//
// Each pixel's value is 683 lm/W × the Rec.709 luminance row of its RGB:
// luminance in cd/m² for a radiance image (W·sr⁻¹·m⁻²), illuminance in lux for
// an irradiance image (W·m⁻²). The value is placed on a linear or log10 scale
// between MIN and MAX and coloured with Google's Turbo map (Mikhailov 2019,
// Ruofei Du's polynomial fit): dark blue at MIN, through green and yellow, to
// dark red at MAX; values outside clamp to the ends, NaN/Inf are magenta.
#pragma once

#include <optional>
#include <vector>

#include "io/image.h"

namespace radiant {

enum class FalseColourQuantity { Luminance, Illuminance };

struct FalseColourSettings {
  FalseColourQuantity quantity = FalseColourQuantity::Luminance;
  /// The scale's ends in cd/m² or lux. Default (both empty): MAX is the largest
  /// value among pixels that show no emitter (display/emitter_mask.h),
  /// rounded up to 1, 2 or 5 × 10^k (to 10^k with a log scale); MIN is 0, or
  /// MAX/1000 (three decades) with a log scale.
  std::optional<double> minimum, maximum;
  bool logarithmic = false;
  bool legend = false;  ///< add a scale bar with labelled ticks to the right of the image
};

struct FalseColourImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;   ///< 8-bit sRGB-encoded
  double minimum = 0, maximum = 0;  ///< the scale used
};

/// Throws InputError at --range for a scale that cannot be drawn (MIN ≥ MAX, MIN ≤ 0 with --log).
FalseColourImage falseColour(const Image &image, const FalseColourSettings &settings);

/// The Turbo colour of x ∈ [0, 1], sRGB-encoded 8-bit.
void turboColour(double x, unsigned char rgb[3]);

}  // namespace radiant
