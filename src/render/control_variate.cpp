#include "render/control_variate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

void ControlVariateImage::restore(Sums sums) {
  if (sums.controls.width != width_ || sums.controls.height != height_ || sums.pairs.width != width_ ||
      sums.pairs.height != height_ || !sums.controls.channels.empty())
    throw std::invalid_argument("ControlVariateImage::restore: sums of another image");
  controls_ = std::move(sums.controls);
  pairs_ = std::move(sums.pairs);
  controlSpp_ = sums.controlSpp, pairedSpp_ = sums.pairedSpp;
}

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

void ControlVariateImage::addPairs(const Film &film) {
  const FilmChannel *c = film.channel("control");
  if (!c) throw std::logic_error("a paired film needs the channel 'control'");
  for (size_t p = 0; p < film.pixelCount(); ++p) {
    pairs_.sumControl[p] += c->sum[p], pairs_.sumControlSquares[p] += c->sumSquares[p];
    pairs_.sumDifference[p] += c->sumDifference[p], pairs_.sumDifferenceSquares[p] += c->sumDifferenceSquares[p];
    pairs_.sumProducts[p] += c->sumProducts[p], pairs_.samples[p] += film.samples[p];
    controls_.sum[p] += c->sum[p], controls_.sumSquares[p] += c->sumSquares[p];
    controls_.samples[p] += film.samples[p];
  }
  if (film.pixelCount()) controlSpp_ += int(film.samples[0]), pairedSpp_ += int(film.samples[0]);
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

double ControlVariateImage::mse(const TileStats &t, double nR, double nP) {
  if (nR < 1) return INFINITY;
  // Without pairs the image is R̄, biased by b; with them R̄ + D̄, unbiased.
  if (nP < 1) return t.bias2 + t.varianceR / nR;
  return std::max(0.0, (t.varianceR + 2 * t.covarianceRD) / nR + t.varianceD / nP);
}

double ControlVariateImage::meanMse(const std::vector<TileStats> &tiles, double nR, double nP) {
  double sum = 0, pixels = 0;
  for (const TileStats &t : tiles) {
    sum += t.pixels * mse(t, nR, nP);
    pixels += t.pixels;
  }
  return pixels > 0 ? sum / pixels : 0;
}

double ControlVariateImage::forecastMse(double moreControls, double morePairs) const {
  return meanMse(tileStats(), controlSpp_ + moreControls + morePairs, pairedSpp_ + morePairs);
}

Image ControlVariateImage::mean(ControlVariateStats *stats) const {
  Image image(width_, height_);
  for (size_t p = 0; p < controls_.pixelCount(); ++p) {
    // R̄ + D̄ with weight 1 on D̄ (control_variate.h: any other weight, or
    // one estimated from these samples, biases the image).
    const PixelStats s = pixelStats(controls_, pairs_, p);
    const Bands value = s.meanR + s.meanD;
    for (int b = 0; b < 3; ++b) image.rgb[3 * p + b] = float(value[b]);
  }
  if (stats) {
    const std::vector<TileStats> tiles = tileStats();
    double bias2 = 0, pixels = 0;
    for (const TileStats &t : tiles) bias2 += t.pixels * t.bias2, pixels += t.pixels;
    stats->biasRms = pixels > 0 ? std::sqrt(bias2 / pixels) : 0;
    stats->predictedRmse = std::sqrt(meanMse(tiles, controlSpp_, pairedSpp_));
  }
  return image;
}

Image ControlVariateImage::variance() const {
  Image image(width_, height_);
  for (size_t p = 0; p < controls_.pixelCount(); ++p) {
    const PixelStats s = pixelStats(controls_, pairs_, p);
    for (int b = 0; b < 3; ++b) {
      // Var(R̄ + D̄) = Var R̄ + Var D̄ + 2 Cov(R̄, D̄), Cov(R̄, D̄) = C_RD / n_R (the pairs' R are in R̄).
      double v = s.nR >= 1 ? (s.varianceR[b] + 2 * s.covarianceRD[b]) / s.nR : 0;
      if (s.nP >= 1) v += s.varianceD[b] / s.nP;
      image.rgb[3 * p + b] = float(std::max(0.0, v));
    }
  }
  return image;
}

}  // namespace radiant
