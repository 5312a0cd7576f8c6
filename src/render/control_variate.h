// The radiosity solution as a control variate (C&W §9.3.2: "in later passes
// the solution is … used as a control variate, so that the last passes are
// unbiased"; docs/multipass.md).
//
// Two estimators of each pixel, from the same path tracer:
//   R — the path reads the solution's reflected radiosity after one
//       non-specular bounce (rushmeier-like): cheap, low variance, biased
//       by the solution's error b = E[R] − E[P];
//   P — the same path continued to its end: `path`'s estimator, number for
//       number, so E[P] is exactly `path`'s expected value.
// Paired samples give both from the same random numbers, so D = P − R is
// small where the solution is good. With n_R samples of R (from R-only
// rounds and from the pairs) and n_P pairs, the pixel's estimate is
//
//   I = R̄ + D̄,   E[I] = E[R] + E[P − R] = E[P]:
//
// unbiased, not only consistent, for every n_R ≥ n_P ≥ 1, as long as every
// R sample has the same expectation (one solution; no photon map whose
// radius shrinks from sample to sample) and the numbers of samples are fixed
// before the samples are drawn. This is the control variate whose mean is
// not known but estimated from more, cheaper samples: the two-model
// multifidelity Monte Carlo estimator of Peherstorfer, Willcox & Gunzburger,
// "Optimal model management for multifidelity Monte Carlo estimation" (SIAM
// J. Sci. Comput. 2016), with its coefficient α = 1. Rousselle, Jarosz &
// Novák, "Image-space control variates for rendering" (SIGGRAPH Asia 2016),
// render a control image and a difference image the same way (their
// fig. 1: many samples of the control, few of the difference).
//
// Why the weight of D̄ is 1 and not estimated: the version before issue 17
// weighed D̄ by λ ∈ [0, 1] chosen per tile to minimise the mean squared error,
// from the same samples. Any λ < 1 leaves (1 − λ)·b of R's bias in the image
// (2.4 % dark at 60 s on the specular box), and a λ estimated from the
// samples it weighs is biased even when its expectation is 1 (Glynn &
// Szechtman, "Some new perspectives on the method of control variates",
// 2002: a coefficient estimated from the same samples leaves an O(1/n) bias;
// only a fixed one, or one from independent samples, keeps the estimator
// unbiased). With weight 1, R lowers the variance only by what it explains
// of P's (V_P − V_D per sample, below); where that is little, the scheduler
// buys pairs and the image is `path`'s (the specular box: docs/multipass.md).
//
// The same per-sample statistics forecast the image's variance after more
// samples of either kind,
//
//   MSE(n_R, n_P) = (V_R + 2 C_RD) / n_R + V_D / n_P
//
// (V_R, V_D the per-sample variances of R and D, C_RD their covariance; the
// pairs' R are among the n_R), which decides what multipass renders next.
// It depends on the data only through image-wide second moments, never on a
// pixel's mean, so the schedule it sets does not bias the image
// (tests/multipass_bias_test.cpp measures that it does not).
#pragma once

#include <vector>

#include "io/image.h"
#include "render/film.h"

namespace radiant {

struct ControlVariateStats {
  double biasRms = 0;        ///< √(estimated mean b²) of R, W·sr⁻¹·m⁻²: what D̄ corrects
  double predictedRmse = 0;  ///< √(estimated mean MSE) of the combined image
};

class ControlVariateImage {
 public:
  /// The statistics that forecast the error are pooled per tile of `tileSize`² pixels.
  ControlVariateImage(int width, int height, int tileSize = 16);

  /// An R-only round (path with readSolutionDepth, radiance()).
  void addControls(const Film &controls);
  /// A paired round: its R join the controls.
  void addPairs(const PairedFilm &pairs);
  /// The same from a film whose channel "control" holds R (Renderer::channels),
  /// read in place.
  void addPairs(const Film &film);

  /// The combined image R̄ + D̄ (R̄ alone before any pair) and the variance of each pixel's estimate.
  Image mean(ControlVariateStats *stats = nullptr) const;
  Image variance() const;

  /// The mean squared error over the image predicted after `moreControls`
  /// R-only and `morePairs` paired samples per pixel more (per-sample
  /// variances and the bias as measured so far).
  double forecastMse(double moreControls, double morePairs) const;

  int controlSamples() const { return controlSpp_; }  ///< per pixel, R-only rounds and pairs together
  int pairedSamples() const { return pairedSpp_; }

  /// Everything it has summed: what a checkpoint keeps (render/multipass_checkpoint.h).
  struct Sums {
    Film controls;
    PairedFilm pairs;
    int controlSpp = 0, pairedSpp = 0;
  };
  const Film &controlSums() const { return controls_; }
  const PairedFilm &pairedSums() const { return pairs_; }
  /// Carries on from saved sums (of an image of the same size: std::invalid_argument otherwise).
  void restore(Sums sums);

 private:
  /// Per tile, averaged over its pixels and bands: per-sample variances of R
  /// and D, their per-sample covariance, and the estimated squared bias of R
  /// (reported only: D̄ corrects it whatever its size).
  struct TileStats {
    double varianceR = 0, varianceD = 0, covarianceRD = 0, bias2 = 0;
    size_t pixels = 0;
  };
  std::vector<TileStats> tileStats() const;
  /// The tile's predicted MSE with n_R, n_P samples (R̄ alone, biased, without pairs).
  static double mse(const TileStats &t, double nR, double nP);
  /// The predicted MSE over the image.
  static double meanMse(const std::vector<TileStats> &tiles, double nR, double nP);

  int width_, height_, tileSize_, tilesX_, tilesY_;
  Film controls_;     ///< every R sample
  PairedFilm pairs_;  ///< R and D of the paired samples
  int controlSpp_ = 0, pairedSpp_ = 0;
};

}  // namespace radiant
