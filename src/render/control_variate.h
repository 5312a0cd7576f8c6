// The radiosity solution as a control variate (C&W §9.3.2: "in later passes
// the solution is … used as a control variate, so that the last passes are
// unbiased"; docs/multipass.md).
//
// Two estimators of each pixel, from the same path tracer:
//   R — the path reads the solution's reflected radiosity after one
//       non-specular bounce (rushmeier-like), with the light after specular
//       bounces from a photon map: cheap, low variance, biased by the
//       solution's error and the map's blur, b = E[R] − E[P];
//   P — the same path continued to its end: `path`'s estimator, number for
//       number, so E[P] is exactly `path`'s expected value.
// Paired samples give both from the same random numbers, so D = P − R is
// small where the solution is good. With n_R samples of R (from R-only
// rounds and from the pairs) and n_P pairs, the per-pixel estimate
//
//   R̄ + D̄,   E = E[R] + E[P − R] = E[P]
//
// is unbiased (the two-model multifidelity Monte Carlo estimator of
// Peherstorfer, Willcox & Gunzburger, SIAM J. Sci. Comput. 2016, with α = 1;
// the control and difference images of Rousselle, Jarosz & Novák,
// "Image-space control variates for rendering", SIGGRAPH Asia 2016), but D̄
// has P's variance wherever the solution is not what makes P noisy (the
// mirror-and-glass box: 1.03–1.23 × `path`'s RMSE at equal time, issue 37).
//
// The image instead corrects R̄ tile by tile: each pixel gets its tile's mean
// D, added (or spread in proportion to the pixel's R̄: the solution's error is
// often a share of the light). The solution's error is smooth where its own
// variance is not, and a tile of n pixels averages D̄'s noise n-fold. Per
// block of kMaxCorrectionTile² pixels the tile size (32 … 1) and the kind are
// those of least predicted squared error,
//
//   Σ_p (b_p − w_p b_T)²  +  Σ_p w_p² Var D̄_T,
//
// the bias left inside the tiles (estimated from the spread of the pixels' D̄
// about the tile's, less what noise explains) plus the corrections' variance.
// Properties:
// - every tile's corrections sum to Σ_p D̄_p (equal pair counts per pixel),
//   so the sum over any block — and the image's mean — is the unbiased
//   estimator's, whatever tile size the data choose
//   (tests/multipass_bias_test.cpp);
// - consistent: as pairs accumulate, the variance term falls as 1/n_P while
//   a bias left inside a tile does not, so the tiles shrink towards pixels
//   wherever R is biased, and the image converges to `path`'s;
// - where a pixel's tile is one pixel, it is R̄ + D̄ exactly.
// The weight of D̄ in a tile stays 1, never estimated: the λ < 1 of before
// issue 17, chosen from the same samples, left (1 − λ)·b of R's bias in
// the image (Glynn & Szechtman, 2002).
//
// The same statistics forecast the image's squared error after more samples
// of either kind,
//
//   MSE(n_R, n_P) = (V_R + 2 C_RD / n) / n_R + min over tile choices of
//                   (bias left + variance · n_P,now / n_P),
//
// (V_R the per-sample variance of R, C_RD its covariance with D), which
// decides what multipass renders next: more pairs buy smaller tiles.
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

  /// The combined image R̄ + D̃ (R̄ alone before any pair), and each pixel's
  /// variance as the per-pixel estimator R̄ + D̄ has it: summed over a block,
  /// the variance of its mean; per pixel, a bound on the tiles' squared error.
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
  /// Per tile of the forecast, averaged over its pixels and bands: the
  /// per-sample variance of R, its covariance with the correction, and the
  /// estimated squared bias of R (what R̄ alone would leave; reported).
  struct TileStats {
    double varianceR = 0, covarianceRD = 0, bias2 = 0;
    size_t pixels = 0;
  };
  /// A way to correct a block: tiles of `size` pixels on a side, the mean D
  /// added or spread in proportion to R̄ (`scaled`); what it leaves of the
  /// bias, squared, and its variance, both summed over the block's pixels and bands.
  struct CorrectionChoice {
    int size;
    bool scaled;
    double within, variance;
  };
  /// The correction added to each pixel's R̄: the mean D of its correction
  /// tile (added, or spread in proportion to R̄), the tile of
  /// kMaxCorrectionTile pixels on a side or a power of two less, chosen per
  /// block of that size to minimise the predicted squared error.
  struct Correction {
    std::vector<Bands> value, variance;                 ///< the correction, and its variance
    std::vector<double> pixels;                         ///< in the pixel's correction tile
    std::vector<std::vector<CorrectionChoice>> blocks;  ///< every choice, per block
    /// The block's choice of least error when the variances are scaled by `scale`
    /// (1 now; n_P/n_P' after more pairs).
    const CorrectionChoice &best(size_t block, double scale) const;
    /// The best choices' squared error per pixel and band.
    double meanError(double scale) const;
  };
  static constexpr int kMaxCorrectionTile = 32;
  Correction correction() const;
  std::vector<TileStats> tileStats(const Correction &correction) const;
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
