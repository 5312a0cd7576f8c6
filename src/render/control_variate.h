// The radiosity solution as a control variate (C&W §9.3.2: "in later passes
// the solution is … used as a control variate, so that the last passes are
// unbiased"; docs/multipass.md).
//
// Two estimators of each pixel, from the same path tracer:
//   R — the path reads the solution's reflected radiosity after one
//       non-specular bounce (rushmeier-like, plus caustics): cheap, low
//       variance, biased by the solution's error;
//   P — the same path continued to its end: unbiased.
// Paired samples give both from the same random numbers, so D = P − R is
// small where the solution is good. With n_R samples of R (from R-only
// rounds and from the pairs) and n_P pairs, the pixel's estimate is
//
//   I(λ) = R̄ + λ D̄,   0 ≤ λ ≤ 1,
//
// λ = 1 the classical control-variate estimator (unbiased: E[R̄] + E[P − R] = E[P]),
// λ = 0 the solution-reading one. E[D̄] is R's bias b, so with
// V_R = Var R̄, V_D = Var D̄, C = Cov(R̄, D̄) (the pairs' R are in R̄):
//
//   MSE(λ) = (1 − λ)² b² + V_R + 2 λ C + λ² V_D,   λ* = (b² − C) / (b² + V_D).
//
// b² is estimated per tile of pixels from the pairs themselves (E[D̄²] = b² +
// V_D), so λ* → 1 wherever R is biased as the pairs accumulate: the image
// converges to the unbiased answer. R and P each count every light path once;
// I(λ) = (1 − λ) R̄ + λ (R̄ + D̄) weighs two such estimates by weights that
// add to one, so it counts each path once too. The same statistics forecast
// the error after more samples of either kind, which decides what multipass
// renders next.
#pragma once

#include <vector>

#include "io/image.h"
#include "render/film.h"

namespace radiant {

struct ControlVariateStats {
  double meanWeight = 0;     ///< λ averaged over the pixels (0: no pairs yet)
  double biasRms = 0;        ///< √(estimated mean b²) of R, W·sr⁻¹·m⁻²
  double predictedRmse = 0;  ///< √(estimated mean MSE) of the combined image
};

class ControlVariateImage {
 public:
  /// λ is chosen per tile of `tileSize`² pixels (interpolated between tile centres).
  ControlVariateImage(int width, int height, int tileSize = 16);

  /// An R-only round (path with readSolutionDepth, radiance()).
  void addControls(const Film &controls);
  /// A paired round: its R join the controls.
  void addPairs(const PairedFilm &pairs);
  /// The same from a film whose channel "control" holds R (Renderer::channels).
  void addPairs(const Film &film) { addPairs(PairedFilm(film, "control")); }

  /// The combined image R̄ + λ D̄ and the variance of each pixel's estimate.
  Image mean(ControlVariateStats *stats = nullptr) const;
  Image variance() const;

  /// The mean squared error over the image predicted after `moreControls`
  /// R-only and `morePairs` paired samples per pixel more (per-sample
  /// variances and the bias as measured so far).
  double forecastMse(double moreControls, double morePairs) const;

  int controlSamples() const { return controlSpp_; }  ///< per pixel, R-only rounds and pairs together
  int pairedSamples() const { return pairedSpp_; }

 private:
  /// Per tile, averaged over its pixels and bands: per-sample variances of R
  /// and D, their per-sample covariance, and the estimated squared bias of R.
  struct TileStats {
    double varianceR = 0, varianceD = 0, covarianceRD = 0, bias2 = 0;
    size_t pixels = 0;
  };
  std::vector<TileStats> tileStats() const;
  /// The tile's λ* and its predicted MSE with n_R, n_P samples.
  static double bestWeight(const TileStats &t, double nR, double nP);
  static double mse(const TileStats &t, double nR, double nP, double weight);
  /// The predicted MSE over the image, each tile at its λ*.
  static double meanMse(const std::vector<TileStats> &tiles, double nR, double nP);
  /// λ at each pixel, bilinear between the tile centres.
  std::vector<double> pixelWeights(const std::vector<TileStats> &tiles) const;

  int width_, height_, tileSize_, tilesX_, tilesY_;
  Film controls_;     ///< every R sample
  PairedFilm pairs_;  ///< R and D of the paired samples
  int controlSpp_ = 0, pairedSpp_ = 0;
};

}  // namespace radiant
