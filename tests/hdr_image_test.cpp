// Radiance RGBE (.hdr) output: the header Radiance's programs look for, and
// a round trip within RGBE's precision (8-bit mantissas: 1 part in 2⁸ of the
// largest of a pixel's three bands, so within 1 % of it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/image.h"
#include "temp_dir.h"
#include "util/error.h"

namespace radiant {
namespace {

TEST(HdrImage, RoundTripWithinRgbePrecision) {
  Image image(7, 5);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      float *p = image.pixel(x, y);
      // Values over eight decades, coloured, so the shared exponent matters.
      p[0] = float(std::pow(10.0, -3 + x) * 0.37);
      p[1] = float(std::pow(10.0, -3 + x) * (0.5 + 0.1 * y));
      p[2] = float(std::pow(10.0, -3 + x) * 0.05 * (y + 1));
    }
  image.pixel(0, 0)[0] = -1.0f;  // no sign in RGBE: written as 0
  image.pixel(1, 0)[1] = NAN;
  const test::TempDir scratch("hdr");
  const std::string path = scratch.file("radiant_hdr_round_trip.hdr");
  writeImage(image, path);
  {
    std::ifstream in(path, std::ios::binary);
    std::string first, header;
    std::getline(in, first);
    EXPECT_EQ(first, "#?RADIANCE");
    std::string line;
    while (std::getline(in, line) && !line.empty()) header += line + "\n";
    EXPECT_NE(header.find("FORMAT=32-bit_rle_rgbe"), std::string::npos) << header;
    EXPECT_NE(header.find("EXPOSURE="), std::string::npos) << header;
    std::getline(in, line);
    EXPECT_EQ(line, "-Y 5 +X 7");
  }
  const Image back = readImage(path);
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float *a = image.pixel(x, y), *b = back.pixel(x, y);
      double largest = 0;
      for (int k = 0; k < 3; ++k)
        if (std::isfinite(a[k])) largest = std::max(largest, double(a[k]));
      for (int k = 0; k < 3; ++k) {
        const double expected = std::isfinite(a[k]) && a[k] > 0 ? a[k] : 0.0;
        EXPECT_NEAR(b[k], expected, 0.01 * largest) << x << "," << y << " band " << k;
      }
    }
  EXPECT_EQ(back.pixel(0, 0)[0], 0.0f);
  EXPECT_EQ(back.pixel(1, 0)[1], 0.0f);
}

TEST(HdrImage, AnotherFileCalledHdrIsAnInputError) {
  const test::TempDir scratch("hdr");
  const std::string path = scratch.file("radiant_not_an_hdr.hdr");
  std::ofstream(path) << "P3\n1 1\n255\n0 0 0\n";
  EXPECT_THROW(readImage(path), InputError);
  EXPECT_TRUE(isLinearImageExtension("x.hdr"));
}

// Found by the hdr fuzz target (issue 38): a 105-byte file whose resolution
// line claims 3 × 7777772 pixels was decoded, its missing scanlines filled,
// in 9 s and 585 MB. Refused now before stb_image allocates anything.
TEST(HdrImage, AFileShorterThanItsResolutionSaysIsRefusedUnread) {
  const std::string path =
      std::string(RADIANT_SOURCE_DIR) + "/tests/fuzz-regressions/hdr/timeout-hdr-claims-3x7777772-pixels-in-105-bytes";
  const test::TempDir scratch("hdr");
  const std::string copy = scratch.file("radiant_truncated.hdr");
  std::filesystem::copy_file(path, copy, std::filesystem::copy_options::overwrite_existing);
  try {
    readImage(copy);
    ADD_FAILURE() << "accepted";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("truncated: the header says 7777772x3 pixels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radiant
