#include "export/lightmap_encoding.h"

#include <algorithm>
#include <cmath>

#include "io/image.h"

namespace radiant {

std::array<uint8_t, 4> encodeRgbe(const float rgb[3]) {
  const double largest = std::max({double(rgb[0]), double(rgb[1]), double(rgb[2])});
  if (!(largest >= 1e-32) || !std::isfinite(largest)) return {0, 0, 0, 0};
  int exponent = 0;
  const double mantissa = std::frexp(largest, &exponent);  // largest = mantissa·2^exponent, mantissa in [0.5, 1)
  if (exponent > 127) return {255, 255, 255, 255};         // beyond RGBE's range: its largest value
  const double scale = mantissa * 256.0 / largest;
  std::array<uint8_t, 4> out{};
  for (int c = 0; c < 3; ++c)
    out[size_t(c)] = uint8_t(std::clamp(std::floor(std::max(double(rgb[c]), 0.0) * scale), 0.0, 255.0));
  out[3] = uint8_t(exponent + 128);
  return out;
}

std::array<float, 3> decodeRgbe(const std::array<uint8_t, 4> &rgbe) {
  if (rgbe[3] == 0) return {0, 0, 0};
  const double f = std::ldexp(1.0, int(rgbe[3]) - (128 + 8));
  return {float((rgbe[0] + 0.5) * f), float((rgbe[1] + 0.5) * f), float((rgbe[2] + 0.5) * f)};
}

std::vector<unsigned char> lightmapDisplayPng(const LightmapImages &images,
                                              const DisplayLinearFunction &displayLinear) {
  const size_t texels = size_t(images.width) * size_t(images.height);
  std::vector<unsigned char> encoded(3 * texels);
  for (size_t i = 0; i < texels; ++i) {
    double display[3] = {0, 0, 0};
    displayLinear(&images.radiance[3 * i], display);
    for (size_t c = 0; c < 3; ++c)
      encoded[3 * i + c] = (unsigned char)std::lround(255 * std::clamp(srgbEncode(display[c]), 0.0, 1.0));
  }
  return encodePng(encoded, images.width, images.height, 3);
}

std::vector<unsigned char> lightmapIrradiancePng(const LightmapImages &images) {
  const size_t texels = size_t(images.width) * size_t(images.height);
  std::vector<unsigned char> encoded(4 * texels);
  for (size_t i = 0; i < texels; ++i) {
    const std::array<uint8_t, 4> rgbe = encodeRgbe(&images.irradiance[3 * i]);
    std::copy(rgbe.begin(), rgbe.end(), encoded.begin() + std::ptrdiff_t(4 * i));
  }
  return encodePng(encoded, images.width, images.height, 4);
}

}  // namespace radiant
