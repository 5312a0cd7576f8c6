// From the film to images on disk.
#pragma once

#include "io/image.h"
#include "render/film.h"

namespace radiant {

static_assert(kBandCount == 3, "images on disk hold R, G, B; spectral bands need a colour conversion first");

/// An image with one value per pixel taken from the film.
template <typename PerPixel>
Image filmImage(const Film &film, PerPixel value) {
  Image image(film.width, film.height);
  for (size_t p = 0; p < film.pixelCount(); ++p) {
    Bands v = value(p);
    for (int c = 0; c < 3; ++c) image.rgb[3 * p + c] = static_cast<float>(v[c]);
  }
  return image;
}

/// Mean radiance per pixel, W·sr⁻¹·m⁻².
inline Image meanImage(const Film &film) {
  return filmImage(film, [&](size_t p) { return film.mean(p); });
}

/// Variance of each pixel's mean, (W·sr⁻¹·m⁻²)², per band.
inline Image varianceImage(const Film &film) {
  return filmImage(film, [&](size_t p) { return film.varianceOfMean(p); });
}

}  // namespace radiant
