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

const ControlVariateImage::CorrectionChoice &ControlVariateImage::Correction::best(size_t block, double scale) const {
  const CorrectionChoice *best = &blocks[block][0];
  for (const CorrectionChoice &choice : blocks[block])
    if (choice.within + scale * choice.variance < best->within + scale * best->variance) best = &choice;
  return *best;
}

double ControlVariateImage::Correction::meanError(double scale) const {
  double sum = 0;
  for (size_t block = 0; block < blocks.size(); ++block) {
    const CorrectionChoice &choice = best(block, scale);
    sum += choice.within + scale * choice.variance;
  }
  return sum / (double(value.size()) * kBandCount);
}

ControlVariateImage::Correction ControlVariateImage::correction() const {
  Correction c;
  const size_t count = size_t(width_) * height_;
  c.value.assign(count, Bands(0.0));
  c.variance.assign(count, Bands(0.0));
  c.pixels.assign(count, 1.0);
  // Per pixel: R̄, D̄ and the variance of D̄ (0 where it cannot be estimated yet).
  std::vector<Bands> meanR(count), meanD(count), varianceMeanD(count);
  std::vector<double> pairs(count);
  for (size_t p = 0; p < count; ++p) {
    const PixelStats s = pixelStats(controls_, pairs_, p);
    meanR[p] = s.meanR, meanD[p] = s.meanD, pairs[p] = s.nP;
    if (s.nP >= 2) varianceMeanD[p] = s.varianceD / s.nP;
  }
  // One tile, corrected by its mean D added to every pixel, or (scaled) that
  // mean D spread in proportion to each pixel's R̄, w_p = n R̄_p / Σ R̄: the
  // solution's error is often a share of the light, and a tile across a
  // bright and a dark surface then corrects each by its share. Either way the
  // corrections sum to the tile's Σ D̄_p (equal pair counts), so every tile
  // keeps the unbiased estimator's sum. Figures, summed over pixels and
  // bands: the squared bias left inside it, Σ (b_p − w_p b_T)², estimated
  // from E[(D̄_p − w_p D̄_T)²] = (b_p − w_p b_T)² + v_p (1 − 2 w_p/n) + w_p² Var D̄_T,
  // and the variance of the correction, Σ w_p² Var D̄_T.
  struct Tile {
    Bands mean, variance, sumR;
    double within = 0, spread = 0, pixels = 0;
  };
  auto weight = [&](const Tile &t, size_t p, int b, bool scaled) {
    return scaled && t.sumR[b] > 0 ? t.pixels * meanR[p][b] / t.sumR[b] : 1.0;
  };
  auto tileAt = [&](int tx, int ty, int tw, int th, bool scaled) {
    Tile t;
    t.pixels = double(tw) * th;
    Bands sum(0.0), variance(0.0);
    double samples = 0;
    for (int y = ty; y < ty + th; ++y)
      for (int x = tx; x < tx + tw; ++x) {
        const size_t p = size_t(y) * width_ + x;
        sum += pairs_.sumDifference[p], samples += pairs[p], variance += varianceMeanD[p], t.sumR += meanR[p];
      }
    t.mean = samples > 0 ? sum / samples : Bands(0.0), t.variance = variance / sqr(t.pixels);
    for (int y = ty; y < ty + th; ++y)
      for (int x = tx; x < tx + tw; ++x) {
        const size_t p = size_t(y) * width_ + x;
        for (int b = 0; b < kBandCount; ++b) {
          const double w = weight(t, p, b, scaled);
          t.within +=
              sqr(meanD[p][b] - w * t.mean[b]) - varianceMeanD[p][b] * (1 - 2 * w / t.pixels) - sqr(w) * t.variance[b];
          t.spread += sqr(w) * t.variance[b];
        }
      }
    return t;
  };
  const int block = kMaxCorrectionTile;
  for (int by = 0; by < height_; by += block)
    for (int bx = 0; bx < width_; bx += block) {
      const int bw = std::min(block, width_ - bx), bh = std::min(block, height_ - by);
      auto forEachTile = [&](int size, bool scaled, auto &&visit) {
        for (int ty = by; ty < by + bh; ty += size)
          for (int tx = bx; tx < bx + bw; tx += size) {
            const int tw = std::min(size, bx + bw - tx), th = std::min(size, by + bh - ty);
            visit(tx, ty, tw, th, tileAt(tx, ty, tw, th, scaled));
          }
      };
      bool varianceKnown = true;
      for (int y = by; y < by + bh; ++y)
        for (int x = bx; x < bx + bw; ++x) varianceKnown = varianceKnown && pairs[size_t(y) * width_ + x] >= 2;
      // Every tile size and kind: the bias each leaves and its variance now.
      // Without variances (fewer than 2 pairs) the block is one tile.
      std::vector<CorrectionChoice> &candidates = c.blocks.emplace_back();
      for (int size = block; size >= (varianceKnown ? 1 : block); size /= 2)
        for (const bool scaled : {false, true}) {
          CorrectionChoice choice{size, scaled, 0, 0};
          forEachTile(size, scaled, [&](int, int, int, int, const Tile &t) {
            choice.within += std::max(0.0, t.within), choice.variance += t.spread;
          });
          candidates.push_back(choice);
        }
      // The one of least squared error.
      const CorrectionChoice &best = c.best(c.blocks.size() - 1, 1.0);
      forEachTile(best.size, best.scaled, [&](int tx, int ty, int tw, int th, const Tile &t) {
        for (int y = ty; y < ty + th; ++y)
          for (int x = tx; x < tx + tw; ++x) {
            const size_t p = size_t(y) * width_ + x;
            for (int b = 0; b < kBandCount; ++b) {
              const double w = weight(t, p, b, best.scaled);
              c.value[p][b] = w * t.mean[b], c.variance[p][b] = sqr(w) * t.variance[b];
            }
            c.pixels[p] = t.pixels;
          }
      });
    }
  return c;
}

std::vector<ControlVariateImage::TileStats> ControlVariateImage::tileStats(const Correction &correction) const {
  std::vector<TileStats> tiles(size_t(tilesX_) * tilesY_);
  std::vector<Bands> meanBias(tiles.size()), meanBiasVariance(tiles.size());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const size_t p = size_t(y) * width_ + x, t = size_t(y / tileSize_) * tilesX_ + x / tileSize_;
      const PixelStats s = pixelStats(controls_, pairs_, p);
      TileStats &tile = tiles[t];
      ++tile.pixels;
      for (int b = 0; b < kBandCount; ++b) {
        // The correction is its tile's mean D: Cov(R̄_p, D̃_p) ≈ C_RD/(n_R·n).
        tile.varianceR += s.varianceR[b], tile.covarianceRD += s.covarianceRD[b] / correction.pixels[p];
        // E[D̄²] = b² + Var D̄: each pixel's share of the squared bias.
        if (s.nP >= 2) tile.bias2 += sqr(s.meanD[b]) - s.varianceD[b] / s.nP;
        meanBias[t][b] += s.meanD[b];
        if (s.nP >= 2) meanBiasVariance[t][b] += s.varianceD[b] / s.nP;
      }
    }
  for (size_t t = 0; t < tiles.size(); ++t) {
    TileStats &tile = tiles[t];
    const double n = double(tile.pixels) * kBandCount, pixels = double(tile.pixels);
    tile.varianceR /= n, tile.covarianceRD /= n, tile.bias2 /= n;
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
  // Without pairs the image is R̄, biased by b; with them the corrections' share is added by the caller.
  if (nP < 1) return t.bias2 + t.varianceR / nR;
  return std::max(0.0, (t.varianceR + 2 * t.covarianceRD) / nR);
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
  const double pairsLater = pairedSpp_ + morePairs;
  const Correction c = correction();
  // More pairs scale the corrections' variance by n_P/n_P' and may make smaller tiles the best.
  const double corrections = pairedSpp_ > 0 ? c.meanError(pairedSpp_ / pairsLater) : 0.0;
  return meanMse(tileStats(c), controlSpp_ + moreControls + morePairs, pairsLater) + corrections;
}

Image ControlVariateImage::mean(ControlVariateStats *stats) const {
  Image image(width_, height_);
  const Correction c = correction();
  for (size_t p = 0; p < controls_.pixelCount(); ++p) {
    // R̄ + D̃: the mean D of the pixel's correction tile (control_variate.h).
    const Bands value = controls_.mean(p) + c.value[p];
    for (int b = 0; b < 3; ++b) image.rgb[3 * p + b] = float(value[b]);
  }
  if (stats) {
    const std::vector<TileStats> tiles = tileStats(c);
    double bias2 = 0, pixels = 0;
    for (const TileStats &t : tiles) bias2 += t.pixels * t.bias2, pixels += t.pixels;
    stats->biasRms = pixels > 0 ? std::sqrt(bias2 / pixels) : 0;
    stats->predictedRmse =
        std::sqrt(meanMse(tiles, controlSpp_, pairedSpp_) + (pairedSpp_ > 0 ? c.meanError(1.0) : 0.0));
  }
  return image;
}

Image ControlVariateImage::variance() const {
  Image image(width_, height_);
  for (size_t p = 0; p < controls_.pixelCount(); ++p) {
    const PixelStats s = pixelStats(controls_, pairs_, p);
    for (int b = 0; b < 3; ++b) {
      // The per-pixel estimator R̄ + D̄'s variance, Var R̄ + Var D̄ + 2 Cov(R̄, D̄),
      // Cov = C_RD / n_R (the pairs' R are in R̄). Summed over a block it is
      // the variance of the block's mean, which the tiles keep (control_variate.h);
      // per pixel it bounds the tile correction's squared error, bias left included,
      // which was chosen because it predicted less over the block.
      double v = s.nR >= 1 ? (s.varianceR[b] + 2 * s.covarianceRD[b]) / s.nR : 0;
      if (s.nP >= 1) v += s.varianceD[b] / s.nP;
      image.rgb[3 * p + b] = float(std::max(0.0, v));
    }
  }
  return image;
}

}  // namespace radiant
