#include "render/control_variate.h"

#include <algorithm>
#include <cmath>

#include "util/math.h"

namespace radiant {

ControlVariateImage::ControlVariateImage(int width, int height, int tileSize)
    : width_(width),
      height_(height),
      tileSize_(std::max(1, tileSize)),
      tilesX_((width + tileSize_ - 1) / tileSize_),
      tilesY_((height + tileSize_ - 1) / tileSize_),
      controls_(width, height),
      pairs_(width, height) {}

void ControlVariateImage::addControls(const Film &controls) {
  controls_.accumulate(controls);
  if (controls.pixelCount()) controlSpp_ += int(controls.samples[0]);
}

void ControlVariateImage::addPairs(const PairedFilm &pairs) {
  pairs_.accumulate(pairs);
  for (size_t p = 0; p < pairs.pixelCount(); ++p) {
    controls_.sum[p] += pairs.sumControl[p];
    controls_.sumSquares[p] += pairs.sumControlSquares[p];
    controls_.samples[p] += pairs.samples[p];
  }
  if (pairs.pixelCount()) controlSpp_ += int(pairs.samples[0]), pairedSpp_ += int(pairs.samples[0]);
}

namespace {

/// Per-sample statistics of one pixel, per band.
struct PixelStats {
  Bands meanR, meanD, varianceR, varianceD, covarianceRD;
  double nR = 0, nP = 0;
};

PixelStats pixelStats(const Film &controls, const PairedFilm &pairs, size_t p) {
  PixelStats s;
  s.nR = controls.samples[p], s.nP = pairs.samples[p];
  s.meanR = controls.mean(p);
  s.varianceR = controls.varianceOfMean(p) * s.nR;
  if (s.nP >= 1) s.meanD = pairs.sumDifference[p] / s.nP;
  if (s.nP >= 2) {
    const double n = s.nP;
    for (int b = 0; b < kBandCount; ++b) {
      s.varianceD[b] = std::max(0.0, (pairs.sumDifferenceSquares[p][b] - n * sqr(s.meanD[b])) / (n - 1));
      s.covarianceRD[b] = (pairs.sumProducts[p][b] - pairs.sumControl[p][b] * s.meanD[b]) / (n - 1);
    }
  }
  return s;
}

}  // namespace

std::vector<ControlVariateImage::TileStats> ControlVariateImage::tileStats() const {
  std::vector<TileStats> tiles(size_t(tilesX_) * tilesY_);
  std::vector<Bands> meanBias(tiles.size()), meanBiasVariance(tiles.size());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const size_t p = size_t(y) * width_ + x, t = size_t(y / tileSize_) * tilesX_ + x / tileSize_;
      const PixelStats s = pixelStats(controls_, pairs_, p);
      TileStats &tile = tiles[t];
      ++tile.pixels;
      for (int b = 0; b < kBandCount; ++b) {
        tile.varianceR += s.varianceR[b], tile.varianceD += s.varianceD[b], tile.covarianceRD += s.covarianceRD[b];
        // E[D̄²] = b² + Var D̄: each pixel's share of the squared bias.
        if (s.nP >= 2) tile.bias2 += sqr(s.meanD[b]) - s.varianceD[b] / s.nP;
        meanBias[t][b] += s.meanD[b];
        if (s.nP >= 2) meanBiasVariance[t][b] += s.varianceD[b] / s.nP;
      }
    }
  for (size_t t = 0; t < tiles.size(); ++t) {
    TileStats &tile = tiles[t];
    const double n = double(tile.pixels) * kBandCount, pixels = double(tile.pixels);
    tile.varianceR /= n, tile.varianceD /= n, tile.covarianceRD /= n, tile.bias2 /= n;
    // The tile's mean bias squared is a second, far less noisy lower bound on
    // the mean of b² (a smooth error of the solution shows there first): the larger is taken.
    double meanBias2 = 0;
    for (int b = 0; b < kBandCount; ++b)
      meanBias2 += sqr(meanBias[t][b] / pixels) - meanBiasVariance[t][b] / sqr(pixels);
    tile.bias2 = std::max({0.0, tile.bias2, meanBias2 / kBandCount});
  }
  return tiles;
}

double ControlVariateImage::bestWeight(const TileStats &t, double nR, double nP) {
  if (nP < 2 || nR < 1) return 0;  // no pairs (or too few to know D's variance): R alone
  const double denominator = t.bias2 + t.varianceD / nP;
  if (denominator <= 0) return 1;  // R and P agree exactly: either is the answer
  return std::clamp((t.bias2 - t.covarianceRD / nR) / denominator, 0.0, 1.0);
}

double ControlVariateImage::mse(const TileStats &t, double nR, double nP, double weight) {
  if (nR < 1) return INFINITY;
  double m = sqr(1 - weight) * t.bias2 + t.varianceR / nR + 2 * weight * t.covarianceRD / nR;
  if (nP >= 1) m += sqr(weight) * t.varianceD / nP;
  return std::max(0.0, m);
}

double ControlVariateImage::meanMse(const std::vector<TileStats> &tiles, double nR, double nP) {
  double sum = 0, pixels = 0;
  for (const TileStats &t : tiles) {
    sum += t.pixels * mse(t, nR, nP, bestWeight(t, nR, nP));
    pixels += t.pixels;
  }
  return pixels > 0 ? sum / pixels : 0;
}

double ControlVariateImage::forecastMse(double moreControls, double morePairs) const {
  return meanMse(tileStats(), controlSpp_ + moreControls + morePairs, pairedSpp_ + morePairs);
}

std::vector<double> ControlVariateImage::pixelWeights(const std::vector<TileStats> &tiles) const {
  std::vector<double> tileWeight(tiles.size());
  for (size_t t = 0; t < tiles.size(); ++t) tileWeight[t] = bestWeight(tiles[t], controlSpp_, pairedSpp_);
  // Bilinear between tile centres: no seams where λ changes from tile to tile.
  auto axis = [&](int i, int tiles, int &i0, int &i1, double &f) {
    const double u = std::clamp((i + 0.5) / tileSize_ - 0.5, 0.0, double(tiles - 1));
    i0 = int(u), i1 = std::min(i0 + 1, tiles - 1), f = u - i0;
  };
  std::vector<double> weights(size_t(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    int y0, y1;
    double fy;
    axis(y, tilesY_, y0, y1, fy);
    for (int x = 0; x < width_; ++x) {
      int x0, x1;
      double fx;
      axis(x, tilesX_, x0, x1, fx);
      auto at = [&](int tx, int ty) { return tileWeight[size_t(ty) * tilesX_ + tx]; };
      weights[size_t(y) * width_ + x] =
          (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) + fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
    }
  }
  return weights;
}

Image ControlVariateImage::mean(ControlVariateStats *stats) const {
  const std::vector<TileStats> tiles = tileStats();
  const std::vector<double> weights = pixelWeights(tiles);
  Image image(width_, height_);
  double weightSum = 0;
  for (size_t p = 0; p < weights.size(); ++p) {
    const PixelStats s = pixelStats(controls_, pairs_, p);
    const Bands value = s.meanR + s.meanD * weights[p];
    for (int b = 0; b < 3; ++b) image.rgb[3 * p + b] = float(value[b]);
    weightSum += weights[p];
  }
  if (stats) {
    double bias2 = 0, pixels = 0;
    for (const TileStats &t : tiles) bias2 += t.pixels * t.bias2, pixels += t.pixels;
    stats->meanWeight = weights.empty() ? 0 : weightSum / weights.size();
    stats->biasRms = pixels > 0 ? std::sqrt(bias2 / pixels) : 0;
    stats->predictedRmse = std::sqrt(meanMse(tiles, controlSpp_, pairedSpp_));
  }
  return image;
}

Image ControlVariateImage::variance() const {
  const std::vector<double> weights = pixelWeights(tileStats());
  Image image(width_, height_);
  for (size_t p = 0; p < weights.size(); ++p) {
    const PixelStats s = pixelStats(controls_, pairs_, p);
    const double w = weights[p];
    for (int b = 0; b < 3; ++b) {
      double v = s.nR >= 1 ? (s.varianceR[b] + 2 * w * s.covarianceRD[b]) / s.nR : 0;
      if (s.nP >= 1) v += w * w * s.varianceD[b] / s.nP;
      image.rgb[3 * p + b] = float(std::max(0.0, v));
    }
  }
  return image;
}

}  // namespace radiant
