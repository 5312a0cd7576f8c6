// compareImages (radiant compare): the figures of two small images whose
// differences are known, and the pixels left out on request.
#include "io/compare.h"

#include <gtest/gtest.h>

#include <cmath>

#include "display/emitter_mask.h"

namespace radiant {
namespace {

/// A w × h image of one grey value.
Image grey(int w, int h, float value) {
  Image image;
  image.width = w, image.height = h;
  image.rgb.assign(size_t(3) * w * h, value);
  return image;
}

TEST(CompareImages, FiguresOfAKnownDifference) {
  // Reference 0.5 everywhere; the test is 0.5 but for one pixel of 16 at 1.3
  // in red only: red's mean 0.55, its RMSE √(0.8² / 16) = 0.2, the others exact.
  Image reference = grey(4, 4, 0.5f), test = reference;
  test.rgb[3 * 5] = 1.3f;
  const ImageComparison c = compareImages(test, reference);
  EXPECT_EQ(c.pixels, 16u);
  EXPECT_NEAR(c.channels[0].meanTest, 0.55, 1e-7);
  EXPECT_NEAR(c.channels[0].meanRatio, 1.1, 1e-6);
  EXPECT_NEAR(c.channels[0].rmse, 0.2, 1e-7);
  EXPECT_NEAR(c.channels[1].rmse, 0.0, 1e-12);
  EXPECT_NEAR(c.average.rmse, std::sqrt(0.64 / 48), 1e-7);  // over all 48 values
}

TEST(CompareImages, PixelsLeftOutCountForNothing) {
  // A light in pixel (1, 1) of a 4 × 4 image: it and its eight neighbours are
  // left out (display/emitter_mask.h), and so is the test's error there.
  Image reference = grey(4, 4, 0.5f), test = reference;
  reference.emitterFraction.assign(16, 0.0f);
  reference.emitterFraction[1 * 4 + 1] = 0.5f;
  test.rgb[3 * (2 * 4 + 2)] = 9.0f;  // (2, 2): a neighbour of the light
  const ImageComparison all = compareImages(test, reference);
  EXPECT_GT(all.channels[0].rmse, 1.0);
  const ImageComparison lit = compareImages(test, reference, "test", "reference", emitterPixelMask(reference));
  EXPECT_EQ(lit.leftOut, 9u);
  EXPECT_EQ(lit.pixels, 7u);
  EXPECT_NEAR(lit.channels[0].rmse, 0.0, 1e-12);
  EXPECT_NEAR(lit.channels[0].meanRatio, 1.0, 1e-12);
}

}  // namespace
}  // namespace radiant
