// Comparing an image with a reference: what researchers use to rank methods,
// and what our own tests and benchmarks measure error with.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/image.h"

namespace radiant {

struct ChannelComparison {
  double meanTest = 0, meanReference = 0;
  double meanRatio = 0;  ///< meanTest / meanReference (1 is unbiased in mean)
  double rmse = 0;       ///< √(mean (t − r)²), in the images' units
  double relativeMse = 0;///< mean (t − r)² / (r² + ε), ε = 0.01 (Rousselle et al. 2011; pbrt's imgtool)
};

struct ImageComparison {
  std::array<ChannelComparison, 3> channels;  ///< R, G, B
  ChannelComparison average;                  ///< over all channels together
  size_t pixels = 0;
  size_t nonFinitePixels = 0;                 ///< NaN/Inf in the test image (counted, excluded)
};

/// Throws InputError if the sizes differ.
ImageComparison compareImages(const Image &test, const Image &reference, const std::string &testName = "test",
                              const std::string &referenceName = "reference");

/// False-colour map of the signed relative luminance difference (t − r)/r:
/// blue where the test is darker, red where brighter, white where equal,
/// saturating at ±range. Returns 8-bit RGB.
std::vector<unsigned char> differenceImage(const Image &test, const Image &reference, double range);

}  // namespace radiant
