// Comparing an image with a reference: what researchers use to rank methods,
// and what our own tests and benchmarks measure error with.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/image.h"

namespace radiant {

struct ChannelComparison {
  double meanTest = 0, meanReference = 0;
  double meanRatio = 0;    ///< meanTest / meanReference (1 is unbiased in mean)
  double rmse = 0;         ///< √(mean (t − r)²), in the images' units
  double relativeMse = 0;  ///< mean (t − r)² / (r² + ε), ε = 0.01 (Rousselle et al. 2011; pbrt's imgtool)
};

struct ImageComparison {
  std::array<ChannelComparison, 3> channels;  ///< R, G, B
  ChannelComparison average;                  ///< over all channels together
  size_t pixels = 0;
  size_t nonFinitePixels = 0;  ///< NaN/Inf in the test image (counted, excluded)
  size_t leftOut = 0;          ///< pixels left out on request (compareImages' leaveOut)
};

/// Agreement within noise, from the variance of each pixel's mean (radiant
/// render --variance): z-scores of the difference of means, for the whole image
/// and for blocks of pixels, so a bias confined to one wall is not averaged away.
struct NoiseAgreement {
  std::array<double, 3> imageZ{};  ///< (mean test − mean reference) / its standard error, per channel
  size_t blocks = 0;               ///< block × channel z-scores computed
  double blockRmsZ = 0;            ///< ≈ 1 when the images agree within noise
  double blockMaxAbsZ = 0;
  size_t blocksBeyond4 = 0;  ///< |z| > 4: expect ~0.006% by chance
};

/// `testVariance` and `referenceVariance` hold per-pixel variances of the mean
/// (either may be empty: then that image is taken as noise-free).
NoiseAgreement noiseAgreement(const Image &test, const Image &reference, const Image &testVariance,
                              const Image &referenceVariance, int blockSize = 16);

/// Throws InputError if the sizes differ. Pixels whose `leaveOut` entry is
/// non-zero are left out (empty: none), as are non-finite ones.
ImageComparison compareImages(const Image &test, const Image &reference, const std::string &testName = "test",
                              const std::string &referenceName = "reference",
                              const std::vector<uint8_t> &leaveOut = {});

/// False-colour map of the signed relative luminance difference (t − r)/r:
/// blue where the test is darker, red where brighter, white where equal,
/// saturating at ±range. Returns 8-bit RGB.
std::vector<unsigned char> differenceImage(const Image &test, const Image &reference, double range);

}  // namespace radiant
