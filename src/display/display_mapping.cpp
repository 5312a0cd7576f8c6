#include "display/display_mapping.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace radiant {

double srgbDecode(double encoded) {
  if (!(encoded > 0)) return 0;
  if (encoded >= 1) return 1;
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

double gammaEncode(double relativeIntensity, double gamma) {
  if (!(relativeIntensity > 0)) return 0;
  if (relativeIntensity >= 1) return 1;
  return std::pow(relativeIntensity, 1 / gamma);
}

void applyGamutRule(GamutRule rule, double rgb[3]) {
  for (int c = 0; c < 3; ++c)
    if (!(rgb[c] > 0)) rgb[c] = 0;  // negative and NaN
  if (rule == GamutRule::Hue) {
    // Dividing by the largest channel keeps the ratios, hence hue and saturation; +Inf becomes white-ish.
    double largest = std::max({rgb[0], rgb[1], rgb[2]});
    if (largest > 1 && std::isfinite(largest))
      for (int c = 0; c < 3; ++c) rgb[c] /= largest;
  }
  for (int c = 0; c < 3; ++c) rgb[c] = std::min(rgb[c], 1.0);
}

uint16_t quantise(double encoded, int bits) {
  const double top = bits == 16 ? 65535.0 : 255.0;
  return static_cast<uint16_t>(std::lround(top * std::clamp(std::isnan(encoded) ? 0.0 : encoded, 0.0, 1.0)));
}

DisplayMapping::DisplayMapping(const Image &radiance, const DisplaySettings &settings) : settings_(settings) {
  if (settings.bits != 8 && settings.bits != 16)
    throw InputError(InputLocation::ofParameter("bits"), "expected 8 or 16, got " + std::to_string(settings.bits));
  if (settings.transfer == TransferCurve::Gamma && !(settings.gamma > 0 && std::isfinite(settings.gamma)))
    throw InputError(InputLocation::ofParameter("gamma"), "must be a positive number");
  operator_ = findToneOperator(settings.toneOperator).create(radiance, settings.parameters, warnings_);
}

void DisplayMapping::displayLinear(const float radiance[3], double display[3]) const {
  operator_->map(radiance, display);
  applyGamutRule(settings_.gamut, display);
}

void DisplayMapping::encode(const float radiance[3], double encoded[3]) const {
  displayLinear(radiance, encoded);
  for (int c = 0; c < 3; ++c)
    encoded[c] =
        settings_.transfer == TransferCurve::Srgb ? srgbEncode(encoded[c]) : gammaEncode(encoded[c], settings_.gamma);
}

std::vector<uint16_t> DisplayMapping::quantiseImage(const Image &radiance) const {
  std::vector<uint16_t> values(radiance.rgb.size());
  for (size_t p = 0; p < values.size(); p += 3) {
    double encoded[3];
    encode(&radiance.rgb[p], encoded);
    for (int c = 0; c < 3; ++c) values[p + c] = quantise(encoded[c], settings_.bits);
  }
  return values;
}

void DisplayMapping::writePng(const Image &radiance, const std::string &path) const {
  std::vector<uint16_t> values = quantiseImage(radiance);
  if (settings_.bits == 16) return writePng16(values, radiance.width, radiance.height, path);
  std::vector<unsigned char> bytes(values.begin(), values.end());
  writePngBytes(bytes, radiance.width, radiance.height, path);
}

}  // namespace radiant
