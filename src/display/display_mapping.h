// From linear radiance to pixel values: the display mapping of C&W §9.5
// (docs/tone-mapping.md). Four steps, each replaceable:
//
//   1. a tone operator (tone_operator.h): radiance → display-linear I/k per channel;
//   2. the out-of-gamut rule: negative channels to 0, then channels above full
//      scale either clipped one by one (`clip`, the default) or the whole colour
//      divided by its largest channel (`hue`, as SpectraToRGB in Chen's rad.c, Graphics Gems II, does);
//   3. the transfer curve: the sRGB curve (IEC 61966-2-1, the default) or the
//      display model I = k·V^γ inverted, V = (I/k)^(1/γ) (C&W eq. 9.12–9.14);
//   4. quantisation without dithering: round(V · (2^bits − 1)), 8 or 16 bits.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "display/tone_operator.h"
#include "io/image.h"

namespace radiant {

enum class TransferCurve { Srgb, Gamma };
enum class GamutRule { Clip, Hue };

struct DisplaySettings {
  std::string toneOperator = "linear";
  ToneParameters parameters;
  TransferCurve transfer = TransferCurve::Srgb;
  double gamma = 2.2;  ///< TransferCurve::Gamma: the display's γ (for tumblin-rushmeier its γd)
  GamutRule gamut = GamutRule::Clip;
  int bits = 8;  ///< 8 or 16
};

/// The sRGB decoding curve (encoded [0,1] → linear); srgbEncode is in io/image.h.
double srgbDecode(double encoded);
/// V = (I/k)^(1/γ), clamped to [0, 1].
double gammaEncode(double relativeIntensity, double gamma);
/// Applies the gamut rule in place: afterwards every channel is in [0, 1] (NaN → 0).
void applyGamutRule(GamutRule rule, double rgb[3]);
/// round(V · (2^bits − 1)) for V clamped to [0, 1].
uint16_t quantise(double encoded, int bits);

/// A display mapping fixed for one image (the operator adapts to it).
class DisplayMapping {
 public:
  /// Throws InputError for an unknown operator or bits other than 8 or 16.
  DisplayMapping(const Image &radiance, const DisplaySettings &settings);
  /// Encoded values V ∈ [0, 1] for one pixel (steps 1–3).
  void encode(const float radiance[3], double encoded[3]) const;
  /// Steps 1 and 2 only: display-linear I/k per channel in [0, 1], before the
  /// transfer curve (what glTF's linear vertex colours hold).
  void displayLinear(const float radiance[3], double display[3]) const;
  /// Every pixel, quantised: 3 values per pixel, 0 … 2^bits − 1.
  std::vector<uint16_t> quantiseImage(const Image &radiance) const;
  /// Writes a PNG of the image at settings.bits, atomically.
  void writePng(const Image &radiance, const std::string &path) const;

  const ToneOperator &toneOperator() const { return *operator_; }
  /// What the user should know: the operator's constants and any warnings.
  std::string describe() const { return operator_->describe(); }
  const ToneWarnings &warnings() const { return warnings_; }

 private:
  DisplaySettings settings_;
  ToneWarnings warnings_;
  std::unique_ptr<ToneOperator> operator_;
};

}  // namespace radiant
