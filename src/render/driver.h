// The render driver: owns tiles, threads, seeds, sample counts, time budgets
// and progress, so a renderer only estimates radiance for one camera ray.
//
// Determinism: sample s of pixel p always draws its numbers from
// Sampler(seed, p, s) (render/sampler.h) and pixels accumulate their
// samples in index order, so the image depends on the seed and the sample
// count, never on the thread count or the tiling. A time budget only chooses
// how many samples are taken.
//
// Converged pixels: for a renderer whose estimate varies only across the
// pixel (Renderer::variesOnlyAcrossThePixel: the radiosity displays), a
// pixel stops taking samples once, after at least kMinimumSamples, the
// standard error of its mean is below kPixelTolerance of its value (plus a
// tenth of the image's mean, for dark pixels): a pixel inside one surface
// has converged after a few samples, and the rest of the time goes to the
// edges, whose antialiasing is then what the image's error is made of. A
// pixel on an edge (a neighbour's mean differs by more than kEdgeContrast)
// never stops early: where an edge barely crosses a pixel, its first
// samples may all have missed it, and their zero variance says nothing.
// Which pixels stop is decided between rounds from the film alone, so it
// too is the same for every thread count.
//
// Several processes (MPI, cluster/cluster.h): rank r takes every tile t with
// t mod N = r, and after each round the ranks sum their films, so every rank
// holds the whole film before deciding which pixels have converged. A pixel
// is one rank's alone and x + 0 = x, so the summed film is bit for bit the
// one process's film, whatever N. Under a time budget rank 0's clock decides
// the rounds.
//
// Checkpoints (render/checkpoint.h): with a checkpoint path, a round's tiles
// are taken in waves, and between waves, every checkpoint interval, the
// state is saved (by rank 0, the ranks' tiles summed on it); once more when
// interrupted. Resuming redoes the unfinished tiles of the saved round.
#pragma once

#include <functional>
#include <string>

#include "render/film.h"
#include "render/renderer.h"
#include "scene/camera.h"

namespace radiant {

struct DriverOptions {
  int samplesPerPixel = 64;
  double timeBudgetSeconds = 0;  ///< 0: none; else stop after the round that reaches it
  uint64_t seed = 1;
  /// The index of the first sample (render/sampler.h): a render that goes on
  /// from `firstSample` samples of the same seed continues their
  /// low-discrepancy sequence rather than starting another.
  uint64_t firstSample = 0;
  int threads = 0;  ///< 0: all hardware threads
  int tileSize = 16;
  /// Restrict rendering to one pixel (debugging); −1 for the whole image.
  int onlyPixelX = -1, onlyPixelY = -1;
  /// Let converged pixels stop (only for a renderer that varies only across the pixel).
  bool stopConvergedPixels = true;
  /// Save a checkpoint here (render/checkpoint.h) every checkpointIntervalSeconds; empty: never.
  std::string checkpointPath;
  double checkpointIntervalSeconds = 10;
  /// Carry on from checkpointPath's checkpoint when the file exists.
  bool resume = false;
  /// The job's fingerprint, written into the checkpoint and required of one resumed.
  std::string checkpointJob;
  /// Save a checkpoint when the render completes too: a spectral pass's
  /// film, which the passes after it must not lose to a kill.
  bool checkpointWhenDone = false;
};

constexpr int kMinimumSamples = 8;
/// 2·10⁻³: against 10⁻³ the images differ by an RMSE of 7·10⁻⁵ (the
/// Cornell box, cornell-knots and the Wuson at 256²), a fourteenth of the
/// Cornell box's target error, and take 20–35 % less time (the knots'
/// whole run 9.6 → 8.3 s).
constexpr double kPixelTolerance = 2e-3;
/// A pixel whose mean differs from a neighbour's by more than this fraction
/// of the brighter (plus a tenth of the image's mean) lies on an edge, and
/// does not stop, whatever its variance.
constexpr double kEdgeContrast = 0.25;

struct Progress {
  int samplesDone = 0;  ///< complete samples per pixel so far
  int samplesTarget = 0;
  double timeBudgetSeconds = 0;  ///< > 0 when a time budget decides the end
  double fraction = 0;           ///< of the current estimate of total work
  double elapsedSeconds = 0;
  double etaSeconds = 0;  ///< < 0 when unknown
};

struct RenderStats {
  /// The most any pixel took (all of them, unless converged pixels stopped);
  /// after an interrupt, the complete rounds (some pixels have more).
  int samplesPerPixel = 0;
  bool interrupted = false;  ///< stopped early by Ctrl-C (util/interrupt.h)
  /// Carried on from a checkpoint that had this many complete samples per pixel (−1: started afresh).
  int resumedFromSamples = -1;
  int checkpointsWritten = 0;
  double seconds = 0;
  uint64_t cameraSamples = 0;
};

using ProgressCallback = std::function<void(const Progress &)>;

/// Renders into `film` (which must be sized already), and into its channels
/// the renderer's outputs of those names (Renderer::channels; a name it does
/// not give is a std::logic_error). Calls `progress` from the calling
/// thread's context, at most a few times a second.
RenderStats renderImage(const PinholeCamera &camera, const Renderer &renderer, const DriverOptions &options, Film &film,
                        const ProgressCallback &progress = {});

/// A progress reporter for a terminal (bar with ETA on one line) or for logs
/// (a plain line every few seconds), chosen by whether stderr is a terminal.
ProgressCallback makeConsoleProgress(const std::string &label);

}  // namespace radiant
