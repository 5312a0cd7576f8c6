// The numbers a camera sample draws: low-discrepancy first, random after.
//
// The first kQuasiRandomDimensions numbers of sample s of a pixel are the
// s-th point of Roberts' R_d sequence (the additive recurrence
// x_s = frac(offset + s·α), α_k = φ_d^−k with φ_d the positive root of
// x^(d+1) = x + 1), shifted per pixel by random offsets (Cranley–Patterson
// rotation). They cover their unit cube evenly for any prefix of s, so the
// sampling error of a smooth integrand over those dimensions — pixel area,
// the emitter point, the first bounce's direction — falls almost as 1/N
// rather than 1/√N, however many samples a time budget ends up taking.
// Every point is uniformly distributed over the random offsets, so each
// estimate stays unbiased. Later numbers come from the sample's own PCG
// stream. Deterministic: everything depends on (seed, pixel, sample).
#pragma once

#include <array>
#include <cmath>

#include "util/random.h"

namespace radiant {

class Sampler {
 public:
  static constexpr int kQuasiRandomDimensions = 8;
  /// A pixel's Cranley–Patterson offsets: the same for every sample of the
  /// pixel, so the driver draws them once per pixel, not once per sample.
  using PixelOffsets = std::array<double, kQuasiRandomDimensions>;

  static PixelOffsets pixelOffsets(uint64_t seed, uint64_t pixel) {
    Pcg32 offsets = sampleGenerator(seed ^ 0x5bd1e995ULL, pixel, ~uint64_t(0));
    PixelOffsets shift{};
    for (double &x : shift) x = offsets.next();
    return shift;
  }

  /// Plain pseudo-random numbers from `rng` (tests, single-ray queries).
  explicit Sampler(const Pcg32 &rng) : rng_(rng), rngReady_(true), dimension_(kQuasiRandomDimensions) {}
  /// Camera sample `sample` of pixel `pixel`.
  Sampler(uint64_t seed, uint64_t pixel, uint64_t sample) : Sampler(pixelOffsets(seed, pixel), seed, pixel, sample) {}
  /// The same, with the pixel's offsets already drawn (pixelOffsets(seed, pixel)).
  Sampler(const PixelOffsets &offsets, uint64_t seed, uint64_t pixel, uint64_t sample)
      : offsets_(offsets), seed_(seed), pixel_(pixel), sample_(sample) {}

  /// Uniform in [0, 1). The quasi-random numbers and the sample's own
  /// generator are made when first asked for: a display method draws only
  /// the two that place the sample in its pixel.
  double next() {
    if (dimension_ < kQuasiRandomDimensions) {
      // s·α mod 1 in two steps keeps full precision for large s; a − ⌊a⌋
      // is fmod(a, 1) exactly for a ≥ 0 (Sterbenz), at a fraction of its cost.
      const double a = double(sample_) * generators()[dimension_];
      const double x = offsets_[dimension_++] + (a - std::floor(a));
      return x - std::floor(x);
    }
    if (!rngReady_) {
      rng_ = sampleGenerator(seed_, pixel_, sample_);
      rngReady_ = true;
    }
    return rng_.next();
  }

 private:
  /// φ_d: the positive root of x^(d+1) = x + 1 (Newton's method).
  static double generalisedGoldenRatio(int d) {
    double phi = 1.0;
    for (int i = 0; i < 64; ++i) phi -= (std::pow(phi, d + 1) - phi - 1) / ((d + 1) * std::pow(phi, d) - 1);
    return phi;
  }
  /// The pixel position (dimensions 0, 1) uses R_2, the best 2-D lattice of
  /// the family; the rest (the first bounce's numbers) R_6.
  static const std::array<double, kQuasiRandomDimensions> &generators() {
    static const std::array<double, kQuasiRandomDimensions> alpha = [] {
      std::array<double, kQuasiRandomDimensions> a{};
      const double phi2 = generalisedGoldenRatio(2), phiRest = generalisedGoldenRatio(kQuasiRandomDimensions - 2);
      for (int k = 0; k < 2; ++k) a[k] = std::fmod(std::pow(phi2, -(k + 1)), 1.0);
      for (int k = 2; k < kQuasiRandomDimensions; ++k) a[k] = std::fmod(std::pow(phiRest, -(k - 1)), 1.0);
      return a;
    }();
    return alpha;
  }

  PixelOffsets offsets_{};
  uint64_t seed_ = 0, pixel_ = 0, sample_ = 0;
  Pcg32 rng_;
  bool rngReady_ = false;
  int dimension_ = 0;  ///< the next quasi-random dimension; kQuasiRandomDimensions once all are drawn
};

}  // namespace radiant
