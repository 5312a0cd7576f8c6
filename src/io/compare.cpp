#include "io/compare.h"

#include <cmath>

#include "util/error.h"

namespace radiant {

ImageComparison compareImages(const Image &test, const Image &reference, const std::string &testName,
                              const std::string &referenceName, const std::vector<uint8_t> &leaveOut) {
  if (test.width != reference.width || test.height != reference.height)
    throw InputError(InputLocation{testName}, "image is " + std::to_string(test.width) + "x" +
                                                  std::to_string(test.height) + " but the reference '" + referenceName +
                                                  "' is " + std::to_string(reference.width) + "x" +
                                                  std::to_string(reference.height));
  constexpr double kEpsilon = 0.01;
  ImageComparison result;
  std::array<double, 3> sumT{}, sumR{}, sumSq{}, sumRel{};
  size_t n = 0;
  const size_t pixels = size_t(test.width) * test.height;
  for (size_t p = 0; p < pixels; ++p) {
    if (p < leaveOut.size() && leaveOut[p]) {
      ++result.leftOut;
      continue;
    }
    const float *t = &test.rgb[3 * p], *r = &reference.rgb[3 * p];
    if (!std::isfinite(t[0]) || !std::isfinite(t[1]) || !std::isfinite(t[2]) || !std::isfinite(r[0]) ||
        !std::isfinite(r[1]) || !std::isfinite(r[2])) {
      ++result.nonFinitePixels;
      continue;
    }
    ++n;
    for (int c = 0; c < 3; ++c) {
      double d = double(t[c]) - r[c];
      sumT[c] += t[c];
      sumR[c] += r[c];
      sumSq[c] += d * d;
      sumRel[c] += d * d / (double(r[c]) * r[c] + kEpsilon);
    }
  }
  result.pixels = n;
  if (n == 0) return result;
  ChannelComparison &all = result.average;
  for (int c = 0; c < 3; ++c) {
    ChannelComparison &ch = result.channels[c];
    ch.meanTest = sumT[c] / n;
    ch.meanReference = sumR[c] / n;
    ch.meanRatio = ch.meanReference != 0 ? ch.meanTest / ch.meanReference : (ch.meanTest == 0 ? 1 : INFINITY);
    ch.rmse = std::sqrt(sumSq[c] / n);
    ch.relativeMse = sumRel[c] / n;
    all.meanTest += ch.meanTest / 3;
    all.meanReference += ch.meanReference / 3;
    all.rmse += sumSq[c] / (3.0 * n);
    all.relativeMse += ch.relativeMse / 3;
  }
  all.rmse = std::sqrt(all.rmse);
  all.meanRatio = all.meanReference != 0 ? all.meanTest / all.meanReference : (all.meanTest == 0 ? 1 : INFINITY);
  return result;
}

std::vector<unsigned char> differenceImage(const Image &test, const Image &reference, double range) {
  std::vector<unsigned char> out(size_t(test.width) * test.height * 3);
  auto luminance = [](const float *c) { return 0.2126390 * c[0] + 0.7151687 * c[1] + 0.0721923 * c[2]; };
  for (size_t p = 0; p < size_t(test.width) * test.height; ++p) {
    double yt = luminance(&test.rgb[3 * p]), yr = luminance(&reference.rgb[3 * p]);
    double relative = (yt - yr) / std::max(std::abs(yr), 1e-3);
    double s = std::isfinite(relative) ? std::clamp(relative / range, -1.0, 1.0) : 1.0;
    // Diverging blue–white–red: fade the other channels towards the signed colour.
    double fade = 1 - std::abs(s);
    unsigned char *o = &out[3 * p];
    if (!std::isfinite(relative)) {
      o[0] = 255;
      o[1] = 0;
      o[2] = 255;  // magenta: NaN/Inf
    } else if (s >= 0) {
      o[0] = 255;
      o[1] = o[2] = static_cast<unsigned char>(std::lround(255 * fade));
    } else {
      o[2] = 255;
      o[0] = o[1] = static_cast<unsigned char>(std::lround(255 * fade));
    }
  }
  return out;
}

NoiseAgreement noiseAgreement(const Image &test, const Image &reference, const Image &testVariance,
                              const Image &referenceVariance, int blockSize) {
  NoiseAgreement result;
  auto variance = [&](const Image &v, size_t p, int c) { return v.rgb.empty() ? 0.0 : double(v.rgb[3 * p + c]); };
  // The pixels are independent estimates, so variances of sums add.
  auto zScore = [&](int x0, int y0, int x1, int y1, int c) {
    double difference = 0, var = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        size_t p = size_t(y) * test.width + x;
        difference += double(test.rgb[3 * p + c]) - reference.rgb[3 * p + c];
        var += variance(testVariance, p, c) + variance(referenceVariance, p, c);
      }
    // NaN marks a block that carries no information (noise-free and equal, e.g. black in both).
    return var > 0 ? difference / std::sqrt(var) : (difference == 0 ? NAN : INFINITY);
  };
  for (int c = 0; c < 3; ++c) result.imageZ[c] = zScore(0, 0, test.width, test.height, c);
  double sumSquares = 0;
  for (int y = 0; y < test.height; y += blockSize)
    for (int x = 0; x < test.width; x += blockSize)
      for (int c = 0; c < 3; ++c) {
        double z = zScore(x, y, std::min(x + blockSize, test.width), std::min(y + blockSize, test.height), c);
        if (std::isnan(z)) continue;
        ++result.blocks;
        sumSquares += z * z;
        result.blockMaxAbsZ = std::max(result.blockMaxAbsZ, std::abs(z));
        if (std::abs(z) > 4) ++result.blocksBeyond4;
      }
  result.blockRmsZ = result.blocks ? std::sqrt(sumSquares / result.blocks) : 0;
  return result;
}

}  // namespace radiant
