// The solution as a control variate (render/control_variate.h): the combined
// image R̄ + D̄ and the error forecast, on synthetic samples whose truth, bias
// and variances are known.
#include "render/control_variate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/math.h"
#include "util/random.h"

namespace radiant {
namespace {

constexpr int kImageSize = 32;  // 2 × 2 tiles of 16 pixels
constexpr double kTruth = 1.0;  // every pixel, every band

/// Samples of R = truth + bias + e and P = truth + a·e + s·g (e ~ N(0, σ_R²),
/// g ~ N(0, 1)): D = P − R = −bias + (a − 1)·e + s·g, so R is biased by
/// `bias` (plus `checker` on the pixels of one colour of a checkerboard, minus
/// it on the other; plus `step` on the image's left half), and a and s set
/// D's variance and its covariance with R.
struct SyntheticPixels {
  double bias, sigmaR, a, s;
  Pcg32 rng;
  double checker = 0, step = 0;

  double biasAt(size_t p) const {
    const size_t x = p % kImageSize, y = p / kImageSize;
    return bias + ((x + y) % 2 ? checker : -checker) + (x < kImageSize / 2 ? step : 0);
  }

  double gaussian() {  // Box–Muller
    const double u1 = std::max(1e-300, rng.next()), u2 = rng.next();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
  }
  void controls(ControlVariateImage &image, int spp) {
    Film film(kImageSize, kImageSize);
    for (size_t p = 0; p < film.pixelCount(); ++p)
      for (int k = 0; k < spp; ++k) {
        Bands r;
        for (int b = 0; b < kBandCount; ++b) r[b] = kTruth + biasAt(p) + sigmaR * gaussian();
        film.add(p, r);
      }
    image.addControls(film);
  }
  void pairs(ControlVariateImage &image, int spp) {
    Film film(kImageSize, kImageSize, {"control"});
    for (size_t p = 0; p < film.pixelCount(); ++p)
      for (int k = 0; k < spp; ++k) {
        Bands r, unbiased;
        for (int b = 0; b < kBandCount; ++b) {
          const double e = sigmaR * gaussian();
          r[b] = kTruth + biasAt(p) + e;
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

// Without pairs nothing corrects R's bias: the image is R̄.
TEST(ControlVariate, WithoutPairsTheImageIsTheControlMean) {
  ControlVariateImage image(kImageSize, kImageSize);
  SyntheticPixels pixels{0.1, 0.3, 1, 0.5, Pcg32(1, 2)};
  pixels.controls(image, 16);
  EXPECT_NEAR(meanOf(image.mean()), kTruth + 0.1, 4 * 0.3 / std::sqrt(16.0 * 3 * kImageSize * kImageSize));
  EXPECT_EQ(image.controlSamples(), 16);
  EXPECT_EQ(image.pairedSamples(), 0);
}

// A biased control (b = 0.1, 10 % of the truth) and few pairs: the image is
// unbiased all the same, from the first pairs on (the version before issue
// 17 weighed D̄ by λ* = b²/(b² + σ_D²/n_P) = 0.24 here, and its image was 0.076
// too bright). The measured bias of R is what D̄ corrects. Each image's mean
// over 3072 values has a standard deviation of √(σ_R²/72 + σ_D²/8)/√3072 = 0.0033.
TEST(ControlVariate, TheImageIsUnbiasedWhateverTheControlsBias) {
  const double bias = 0.1, sigmaD = 0.5;
  ControlVariateImage image(kImageSize, kImageSize);
  SyntheticPixels pixels{bias, 0.3, 1, sigmaD, Pcg32(3, 4)};
  pixels.controls(image, 64);
  pixels.pairs(image, 8);
  ControlVariateStats stats;
  const Image mean = image.mean(&stats);
  EXPECT_NEAR(meanOf(mean), kTruth, 4 * 0.0033);
  EXPECT_NEAR(stats.biasRms, bias, 0.02);
  EXPECT_EQ(image.pairedSamples(), 8);
  EXPECT_EQ(image.controlSamples(), 64 + 8);
  // Each pixel is R̄ + D̄ exactly: the mean of its controls and pairs' R, plus the mean of its D.
  ControlVariateImage single(1, 1);
  Film controls(1, 1), pairs(1, 1, {"control"});
  controls.add(0, Bands(1.0)), controls.add(0, Bands(2.0));
  const Bands r3(3.0), r4(4.0);
  pairs.add(0, Bands(5.0), &r3), pairs.add(0, Bands(10.0), &r4);
  single.addControls(controls), single.addPairs(pairs);
  // R̄ = (1 + 2 + 3 + 4)/4 = 2.5, D̄ = ((5 − 3) + (10 − 4))/2 = 4.
  EXPECT_FLOAT_EQ(single.mean().rgb[0], 6.5f);
}

// The forecast is the expected squared error (R̄ + D̃ is unbiased: its
// variance), now and — from the statistics of fewer samples — after more
// samples of either kind; with correlated R and D (a = 0.5: Cov(R, D) =
// −σ_R²/2), averaged over independent runs. The bias alternates by ±0.5 from
// pixel to pixel, so only per-pixel correction tiles leave no bias and the
// correction is D̄ itself. Predicted: (σ_R² + 2 Cov)/n_R + σ_D²/n_P = 0 +
// (σ_R²/4 + s²)/8 = 0.00625 (a wrong sign of the covariance gives 0.0196,
// its omission 0.0129).
TEST(ControlVariate, TheForecastIsTheExpectedError) {
  double predictedNow = 0, measuredNow = 0, predictedLater = 0, measuredLater = 0;
  const int runs = 12;
  for (int run = 0; run < runs; ++run) {
    ControlVariateImage image(kImageSize, kImageSize);
    SyntheticPixels pixels{0.05, 0.4, 0.5, 0.1, Pcg32(100 + run, 7)};
    pixels.checker = 0.5;
    pixels.controls(image, 16);
    pixels.pairs(image, 8);
    ControlVariateStats stats;
    measuredNow += squaredError(image.mean(&stats));
    predictedNow += sqr(stats.predictedRmse);
    predictedLater += image.forecastMse(32, 24);
    pixels.controls(image, 32);
    pixels.pairs(image, 24);
    measuredLater += squaredError(image.mean());
  }
  EXPECT_NEAR(predictedNow / runs, 0.00625, 0.05 * 0.00625);
  // 12 runs × 3072 values: the measured means are within a few % of their expectation.
  EXPECT_NEAR(measuredNow / runs, predictedNow / runs, 0.1 * predictedNow / runs);
  EXPECT_NEAR(measuredLater / runs, predictedLater / runs, 0.1 * predictedLater / runs);
  std::cout << "squared error: predicted " << predictedNow / runs << ", measured " << measuredNow / runs
            << "; after more samples predicted " << predictedLater / runs << ", measured " << measuredLater / runs
            << "\n";
}

// Where the solution's bias is smooth, the correction is the mean D of a whole
// tile, and D̄'s noise is averaged over its pixels. σ_R = 0.3, σ_D = 0.5,
// Cov = 0, 72 R and 8 pairs per pixel: per-pixel D̄ (issue 17's estimator) has
// a squared error of σ_R²/72 + σ_D²/8 = 0.0325; the 32² tile's mean D,
// σ_R²/72 + σ_D²/(8·1024) = 0.00128. A bias that steps by 0.2 in the middle of
// the image needs tiles of 16 or less (one tile of 32 would leave 0.01), and
// the image's mean stays unbiased: over each block the tiles' corrections sum
// to its pixels' D̄ whatever size is chosen.
TEST(ControlVariate, ASmoothBiasIsCorrectedFromTheWholeTile) {
  for (const double step : {0.0, 0.2}) {
    double measured = 0, mean = 0;
    const int runs = 4;
    for (int run = 0; run < runs; ++run) {
      ControlVariateImage image(kImageSize, kImageSize);
      SyntheticPixels pixels{0.1, 0.3, 1, 0.5, Pcg32(200 + run, 9)};
      pixels.step = step;
      pixels.controls(image, 64);
      pixels.pairs(image, 8);
      measured += squaredError(image.mean()), mean += meanOf(image.mean());
    }
    EXPECT_LT(measured / runs, 0.002) << "step " << step;
    // Each image's mean over 3072 values: standard deviation √(σ_R²/72 + σ_D²/8)/√3072 = 0.0033.
    EXPECT_NEAR(mean / runs, kTruth, 4 * 0.0033 / std::sqrt(double(runs))) << "step " << step;
  }
}

}  // namespace
}  // namespace radiant
