// The progressive multi-pass method of Chen, Rushmeier, Miller & Turner
// (SIGGRAPH 1991; C&W §9.3.2; docs/multipass.md): a radiosity preview, then
// passes that replace more and more of the radiosity approximation by Monte
// Carlo estimates, specular light and caustics included, until the image is
// the path-traced answer. Every light path is counted by exactly one
// estimator in every pass (docs/multipass.md has the table).
//
//   pass 1  radiosity preview: an interrupted progressive solution, interpolated
//   pass 2  high frequency: emission and specular chains from the eye, direct
//           light and the brightest reflectors sampled per pixel (kok:
//           light-source reclassification), caustics from light-ray tracing,
//           the rest read from the solution
//   pass 3  low frequency: path tracing of indirect light that reads the
//           solution after one non-specular bounce (rushmeier-like), caustics
//           from a new photon map at every non-specular vertex
//   pass 4  the same, reading the solution after two bounces
//   pass 5… unbiased: path tracing to the end (Russian roulette) with the
//           caustic map, a new map with a smaller radius every pass
//           (progressive photon mapping, Knaus & Zwicker 2011); these passes'
//           samples accumulate, and their image converges to the true solution.
#pragma once

#include <functional>
#include <string>

#include "io/image.h"
#include "radiosity/solution.h"
#include "render/driver.h"
#include "render/renderer.h"

namespace radiant {

struct MultipassOptions {
  double timeBudgetSeconds = 0;  ///< 0: none; otherwise stop after the pass that reaches it
  int samplesPerPixel = 64;      ///< samples per pixel of the unbiased passes together
  uint64_t seed = 1;
  int threads = 0;
  size_t photonsPerPass = 200000;  ///< emitted per caustic map
  double photonRadius = 0;         ///< first map's radius, metres; ≤ 0: 1 % of the scene's diagonal
  RendererOptions renderer;        ///< pixel spread, kok's sources, textures…
};

struct MultipassPass {
  int index = 0;            ///< 1, 2, …
  std::string name;         ///< "radiosity preview", "high frequency", …
  int samplesPerPixel = 0;  ///< of this pass (unbiased passes: accumulated so far)
  double seconds = 0;       ///< wall time of this pass, solving included
  bool unbiased = false;
  size_t causticPhotons = 0;  ///< stored in this pass's map
  double photonRadius = 0;
};

/// What the method needs from the command line: a progressive solution,
/// interrupted after `maxShots` shots (0: to its tolerance).
using MultipassSolver = std::function<Solution(int maxShots)>;
/// Called after each pass with its image (for the unbiased passes: all their samples so far).
using MultipassOutput = std::function<void(const MultipassPass &pass, const Image &mean, const Image &variance)>;
/// A progress reporter for one pass (driver.h), or none.
using MultipassProgress = std::function<ProgressCallback(const std::string &label)>;

/// The registry's entry: multipass is not one renderer; this throws.
std::unique_ptr<Renderer> createMultipassPlaceholder(const RayTracer &tracer, const RendererOptions &options);

/// Runs the passes. Deterministic for the seed: pass k draws from seed + k.
void renderMultipass(const RayTracer &tracer, const PinholeCamera &camera, int width, int height,
                     const MultipassOptions &options, const MultipassSolver &solve, const MultipassOutput &output,
                     const MultipassProgress &progress = {});

}  // namespace radiant
