// From the film to images on disk.
#pragma once

#include "io/image.h"
#include "render/film.h"

namespace radiant {

/// Mean radiance per pixel, W·sr⁻¹·m⁻².
inline Image meanImage(const Film &film) {
  Image image(film.width, film.height);
  for (size_t p = 0; p < film.pixelCount(); ++p) {
    Bands m = film.mean(p);
    for (int c = 0; c < 3; ++c) image.rgb[3 * p + c] = static_cast<float>(m[c]);
  }
  return image;
}

/// Variance of each pixel's mean, (W·sr⁻¹·m⁻²)², per band.
inline Image varianceImage(const Film &film) {
  Image image(film.width, film.height);
  for (size_t p = 0; p < film.pixelCount(); ++p) {
    Bands v = film.varianceOfMean(p);
    for (int c = 0; c < 3; ++c) image.rgb[3 * p + c] = static_cast<float>(v[c]);
  }
  return image;
}

}  // namespace radiant
