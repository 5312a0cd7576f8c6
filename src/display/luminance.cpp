#include "display/luminance.h"

#include <algorithm>
#include <cmath>

namespace radiant {

LuminanceStatistics luminanceStatistics(const Image &image) {
  LuminanceStatistics s;
  double sumLog = 0;
  const size_t pixels = size_t(image.width) * image.height;
  for (size_t p = 0; p < pixels; ++p) {
    const float *rgb = &image.rgb[3 * p];
    if (!std::isfinite(rgb[0]) || !std::isfinite(rgb[1]) || !std::isfinite(rgb[2])) {
      ++s.nonFinitePixels;
      continue;
    }
    double luminance = luminanceCdPerM2(rgb);
    if (!(luminance > 0)) continue;
    sumLog += std::log(luminance);
    s.maximum = std::max(s.maximum, luminance);
    ++s.litPixels;
  }
  s.logAverage = s.litPixels ? std::exp(sumLog / double(s.litPixels)) : 0.0;
  return s;
}

}  // namespace radiant
