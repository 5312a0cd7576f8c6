// The solution as a control variate (render/control_variate.h): the weight of
// the pairs' correction, the combined image and the error forecast, on
// synthetic samples whose truth, bias and variances are known.
#include "render/control_variate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/math.h"
#include "util/random.h"

namespace radiant {
namespace {

constexpr int kSize = 32;       // 2 × 2 tiles of 16 pixels
constexpr double kTruth = 1.0;  // every pixel, every band

/// Samples of R = truth + bias + e and P = truth + a·e + s·g (e ~ N(0, σ_R²),
/// g ~ N(0, 1)): D = P − R = −bias + (a − 1)·e + s·g, so R is biased by
/// `bias`, and a and s set D's variance and its covariance with R.
struct SyntheticPixels {
  double bias, sigmaR, a, s;
  Pcg32 rng;

  double gaussian() {  // Box–Muller
    const double u1 = std::max(1e-300, rng.next()), u2 = rng.next();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
  }
  void controls(ControlVariateImage &image, int spp) {
    Film film(kSize, kSize);
    for (size_t p = 0; p < film.pixelCount(); ++p)
      for (int k = 0; k < spp; ++k) {
        Bands r;
        for (int b = 0; b < kBandCount; ++b) r[b] = kTruth + bias + sigmaR * gaussian();
        film.add(p, r);
      }
    image.addControls(film);
  }
  void pairs(ControlVariateImage &image, int spp) {
    Film film(kSize, kSize, {"control"});
    for (size_t p = 0; p < film.pixelCount(); ++p)
      for (int k = 0; k < spp; ++k) {
        Bands r, unbiased;
        for (int b = 0; b < kBandCount; ++b) {
          const double e = sigmaR * gaussian();
          r[b] = kTruth + bias + e;
          unbiased[b] = kTruth + a * e + s * gaussian();
        }
        film.add(p, unbiased, &r);
      }
    image.addPairs(film);
  }
};

/// Mean squared error of an image against the truth, over pixels and bands.
double squaredError(const Image &image) {
  double sum = 0;
  for (float v : image.rgb) sum += sqr(v - kTruth);
  return sum / image.rgb.size();
}

double meanOf(const Image &image) {
  double sum = 0;
  for (float v : image.rgb) sum += v;
  return sum / image.rgb.size();
}

// Without pairs nothing is known of R's bias: the image is R̄, λ = 0.
TEST(ControlVariate, WithoutPairsTheImageIsTheControlMean) {
  ControlVariateImage image(kSize, kSize);
  SyntheticPixels pixels{0.1, 0.3, 1, 0.5, Pcg32(1, 2)};
  pixels.controls(image, 16);
  ControlVariateStats stats;
  const Image mean = image.mean(&stats);
  EXPECT_EQ(stats.meanWeight, 0);
  EXPECT_NEAR(meanOf(mean), kTruth + 0.1, 4 * 0.3 / std::sqrt(16.0 * 3 * kSize * kSize));
  EXPECT_EQ(image.controlSamples(), 16);
  EXPECT_EQ(image.pairedSamples(), 0);
}

// A biased control: λ* = b² / (b² + σ_D²/n_P) (no covariance here, σ_D = 0.5):
// 0.24 with 8 pairs, 0.976 with 1024, so the image converges to the truth
// as the pairs accumulate; at every stage it is at least as good as either
// R̄ or the unbiased R̄ + D̄ alone.
TEST(ControlVariate, TheWeightGoesToOneWhereTheControlIsBiased) {
  const double bias = 0.1, sigmaD = 0.5;
  ControlVariateImage image(kSize, kSize);
  SyntheticPixels pixels{bias, 0.3, 1, sigmaD, Pcg32(3, 4)};
  pixels.controls(image, 64);
  pixels.pairs(image, 8);
  ControlVariateStats stats;
  Image mean = image.mean(&stats);
  const double expectedFew = sqr(bias) / (sqr(bias) + sqr(sigmaD) / 8);
  // The tile's b² comes from 768 values of D̄² (relative noise ≈ √2 · 3.1/(1 + 3.1) / √768 ≈ 4 %): ±0.05 in λ.
  EXPECT_NEAR(stats.meanWeight, expectedFew, 0.05);
  EXPECT_NEAR(stats.biasRms, bias, 0.02);
  // MSE of the optimum against R̄ alone (b² + σ_R²/72) and R̄ + D̄ alone (σ_R²/72 + σ_D²/8).
  const double controlOnly = sqr(bias) + 0.09 / 72, unbiasedOnly = 0.09 / 72 + sqr(sigmaD) / 8;
  EXPECT_LT(squaredError(mean), 1.1 * std::min(controlOnly, unbiasedOnly));

  pixels.pairs(image, 1016);  // 1024 pairs in all
  mean = image.mean(&stats);
  EXPECT_GT(stats.meanWeight, 0.95);
  EXPECT_NEAR(stats.meanWeight, sqr(bias) / (sqr(bias) + sqr(sigmaD) / 1024), 0.01);
  // What is left: (1 − λ)·b = 0.0024, and noise √(σ_R²/1088 + λ²σ_D²/1024)/√3072 = 3e-4 on the image mean.
  EXPECT_NEAR(meanOf(mean), kTruth, (1 - stats.meanWeight) * bias + 4 * 3e-4);
  EXPECT_EQ(image.pairedSamples(), 1024);
  EXPECT_EQ(image.controlSamples(), 64 + 1024);
}

// An unbiased control: the pairs' correction only adds noise, so λ stays
// near 0 and the image is as good as R̄ over all its samples.
TEST(ControlVariate, AnUnbiasedControlKeepsItsWeight) {
  ControlVariateImage image(kSize, kSize);
  SyntheticPixels pixels{0.0, 0.3, 1, 0.5, Pcg32(5, 6)};
  pixels.controls(image, 64);
  pixels.pairs(image, 8);
  ControlVariateStats stats;
  const Image mean = image.mean(&stats);
  EXPECT_LT(stats.meanWeight, 0.1);
  EXPECT_LT(squaredError(mean), 1.2 * 0.09 / 72);
}

// The forecast is the expected squared error, and λ takes the covariance
// into account: with correlated R and D (a = 0.5: Cov(R, D) = −σ_R²/2),
// averaged over independent runs, the measured
// squared error of the image matches the predicted one, now and — from the
// statistics of fewer samples — after more samples of either kind.
TEST(ControlVariate, TheForecastIsTheExpectedError) {
  double predictedNow = 0, measuredNow = 0, predictedLater = 0, measuredLater = 0;
  const int runs = 12;
  for (int run = 0; run < runs; ++run) {
    ControlVariateImage image(kSize, kSize);
    SyntheticPixels pixels{0.05, 0.4, 0.5, 0.1, Pcg32(100 + run, 7)};
    pixels.controls(image, 16);
    pixels.pairs(image, 8);
    ControlVariateStats stats;
    measuredNow += squaredError(image.mean(&stats));
    predictedNow += sqr(stats.predictedRmse);
    // λ* = (b² − Cov(R̄, D̄))/(b² + Var D̄) with Cov = −σ_R²/2 / n_R = −0.08/24 and
    // Var D̄ = (σ_R²/4 + s²)/n_P = 0.05/8: (0.0025 + 0.00333)/(0.0025 + 0.00625) = 0.667.
    // (A wrong sign of the covariance gives 0, its omission 0.29.)
    EXPECT_NEAR(stats.meanWeight, 0.667, 0.05);
    predictedLater += image.forecastMse(32, 24);
    pixels.controls(image, 32);
    pixels.pairs(image, 24);
    measuredLater += squaredError(image.mean());
  }
  // Better than R̄ alone (b² + σ_R²/24 = 0.00917) by the pairs' correction.
  EXPECT_LT(measuredNow / runs, 0.7 * (0.0025 + 0.16 / 24));
  // 12 runs × 3072 values: the measured means are within a few % of their expectation.
  EXPECT_NEAR(measuredNow / runs, predictedNow / runs, 0.1 * predictedNow / runs);
  EXPECT_NEAR(measuredLater / runs, predictedLater / runs, 0.1 * predictedLater / runs);
  std::cout << "squared error: predicted " << predictedNow / runs << ", measured " << measuredNow / runs
            << "; after more samples predicted " << predictedLater / runs << ", measured " << measuredLater / runs
            << "\n";
}

}  // namespace
}  // namespace radiant
