// The film: linear radiance per band per pixel, with the running statistics a
// variance image needs. Box filter: each camera sample counts fully for the
// pixel it falls in.
#pragma once

#include <cstdint>
#include <vector>

#include "util/spectrum.h"

namespace radiant {

struct Film {
  int width = 0, height = 0;
  std::vector<Bands> sum;         ///< Σ radiance, W·sr⁻¹·m⁻²
  std::vector<Bands> sumSquares;  ///< Σ radiance², for the variance estimate
  std::vector<uint32_t> samples;  ///< sample count per pixel

  Film() = default;
  Film(int w, int h) : width(w), height(h), sum(size_t(w) * h), sumSquares(size_t(w) * h), samples(size_t(w) * h) {}

  size_t pixelCount() const { return size_t(width) * height; }
  void add(size_t pixel, const Bands &radiance) {
    sum[pixel] += radiance;
    sumSquares[pixel] += radiance * radiance;
    ++samples[pixel];
  }
  /// The pixel's estimate: mean radiance.
  Bands mean(size_t pixel) const { return samples[pixel] ? sum[pixel] / samples[pixel] : Bands(0.0); }
  /// Adds another film's samples (same size): the mean of all samples of both.
  void accumulate(const Film &other) {
    for (size_t p = 0; p < pixelCount(); ++p)
      sum[p] += other.sum[p], sumSquares[p] += other.sumSquares[p], samples[p] += other.samples[p];
  }
  /// Variance of the pixel's mean (sample variance / n), per band.
  Bands varianceOfMean(size_t pixel) const {
    uint32_t n = samples[pixel];
    if (n < 2) return Bands(0.0);
    Bands m = sum[pixel] / n;
    Bands v = (sumSquares[pixel] / n - m * m) * (1.0 / (n - 1));
    for (int b = 0; b < kBandCount; ++b) v[b] = std::max(0.0, v[b]);
    return v;
  }
};

/// Paired samples (Renderer::pairedRadiance): per pixel the sums a control
/// variate needs — of the control R, of the difference D = radiance − R, of
/// their squares and of their product (render/control_variate.h).
struct PairedFilm {
  int width = 0, height = 0;
  std::vector<Bands> sumControl, sumControlSquares, sumDifference, sumDifferenceSquares, sumProducts;
  std::vector<uint32_t> samples;

  PairedFilm() = default;
  PairedFilm(int w, int h)
      : width(w),
        height(h),
        sumControl(size_t(w) * h),
        sumControlSquares(size_t(w) * h),
        sumDifference(size_t(w) * h),
        sumDifferenceSquares(size_t(w) * h),
        sumProducts(size_t(w) * h),
        samples(size_t(w) * h) {}

  size_t pixelCount() const { return size_t(width) * height; }
  void add(size_t pixel, const Bands &radiance, const Bands &control) {
    const Bands difference = radiance - control;
    sumControl[pixel] += control;
    sumControlSquares[pixel] += control * control;
    sumDifference[pixel] += difference;
    sumDifferenceSquares[pixel] += difference * difference;
    sumProducts[pixel] += control * difference;
    ++samples[pixel];
  }
  /// Adds another paired film's samples (same size).
  void accumulate(const PairedFilm &other) {
    for (size_t p = 0; p < pixelCount(); ++p) {
      sumControl[p] += other.sumControl[p], sumControlSquares[p] += other.sumControlSquares[p];
      sumDifference[p] += other.sumDifference[p], sumDifferenceSquares[p] += other.sumDifferenceSquares[p];
      sumProducts[p] += other.sumProducts[p], samples[p] += other.samples[p];
    }
  }
};

}  // namespace radiant
