// The progressive multi-pass method of Chen, Rushmeier, Miller & Turner
// (SIGGRAPH 1991; C&W §9.3.2; docs/multipass.md): a radiosity preview, then
// passes that replace more and more of the radiosity approximation by Monte
// Carlo estimates, specular light and caustics included, until the image is
// the path-traced answer. Every light path is counted once by every estimator
// (docs/multipass.md has the table).
//
//   pass 1  radiosity preview: an interrupted progressive solution, interpolated
//   pass 2  high frequency: emission and specular chains from the eye, direct
//           light and the brightest reflectors sampled per pixel (kok:
//           light-source reclassification), caustics from light-ray tracing,
//           the rest read from the solution
//   pass 3… the solution corrected by Monte Carlo (render/control_variate.h):
//           low-frequency passes trace paths that read the solution after one
//           non-specular bounce, with the light that mirrors and glass throw
//           from a photon map (R); paired passes trace the same
//           paths to their end beside R, from the same numbers (P, which is
//           `path`'s estimator exactly). The image is R̄ plus P − R averaged
//           over correction tiles that shrink as pairs accumulate: every
//           tile's sum is the unbiased estimator's, and the image converges
//           to `path`'s. Each pass renders the kind the error forecast
//           favours. All these samples accumulate.
#pragma once

#include <functional>
#include <string>

#include "io/image.h"
#include "radiosity/solution.h"
#include "render/driver.h"
#include "render/renderer.h"
#include "util/parameters.h"

namespace radiant {

struct MultipassOptions {
  double timeBudgetSeconds = 0;  ///< 0: none; otherwise stop after the pass that reaches it
  /// The work of passes 3… together, in paired samples per pixel (a sample
  /// that only reads the solution counts half: render/multipass.cpp)
  int samplesPerPixel = 64;
  uint64_t seed = 1;
  int threads = 0;
  size_t photonsPerPass = 200000;  ///< emitted for pass 2's caustic map
  double photonRadius = 0;         ///< pass 2's map's radius, metres; ≤ 0: 1 % of the scene's diagonal
  RenderContext context;           ///< pixel spread (the passes set the solution and caustics)
  /// --checkpoint (render/multipass_checkpoint.h): saved at the start of
  /// every pass from 3 on, the pass in progress every interval; empty: never.
  std::string checkpointPath, checkpointJob;
  double checkpointIntervalSeconds = 10;
  bool resume = false;  ///< carry on from checkpointPath when it exists
  /// Values for multipassParameters(): max-depth (the path passes), sources,
  /// source-fraction (pass 2's kok), bump-orientations (passes 1 and 2).
  ParameterValues parameters;
};

struct MultipassPass {
  int index = 0;            ///< 1, 2, …
  std::string name;         ///< "radiosity preview", "high frequency", …
  int samplesPerPixel = 0;  ///< of this pass
  double seconds = 0;       ///< wall time of this pass, solving included
  bool unbiased = false;    ///< passes 3…: it rendered paired (unbiased) samples, not only R
  // Passes 3…, all passes so far together (render/control_variate.h):
  int controlSamples = 0;     ///< R samples per pixel (R-only passes and pairs)
  int pairedSamples = 0;      ///< paired samples per pixel
  double estimatedBias = 0;   ///< RMS of R's bias as the pairs measure it, W·sr⁻¹·m⁻²
  size_t causticPhotons = 0;  ///< stored in this pass's map (pass 2)
  double photonRadius = 0;
};

/// What the method needs from the command line: `maxShots` > 0, the preview's
/// progressive solution interrupted after that many shots; 0, the solution
/// the later passes read (the command line's --solver).
using MultipassSolver = std::function<Solution(int maxShots)>;
/// Called after each pass with its image (passes 3…: the combination of all their samples so far).
using MultipassOutput = std::function<void(const MultipassPass &pass, const Image &mean, const Image &variance)>;
/// A progress reporter for one pass (driver.h), or none.
using MultipassProgress = std::function<ProgressCallback(const std::string &label)>;

/// The solver of the solution that passes 3… read, for --solver `requested`:
/// under a time budget "auto" is the stochastic solver, whose solve is a
/// fraction of a second on the boxes (the specular box: 4652 elements) where
/// "auto" elsewhere picks hierarchical-exact (27 701 elements, 8.5 s there).
/// The solution is a control variate: its error raises the variance of the
/// correction, never a block's mean, and a solve no short budget can pay
/// for leaves it no samples.
std::string multipassSolverName(const std::string &requested, double timeBudgetSeconds);

/// One line for a person: what the pass did (samples, time, photons, the control variate's weight).
std::string describePass(const MultipassPass &pass);

/// Runs the passes. Deterministic for the seed: pass k draws from seed + k.
void renderMultipass(const RayTracer &tracer, const PinholeCamera &camera, int width, int height,
                     const MultipassOptions &options, const MultipassSolver &solve, const MultipassOutput &output,
                     const MultipassProgress &progress = {});

}  // namespace radiant
