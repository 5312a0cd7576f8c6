// The table of rendering methods: each entry is a method's name, summary,
// parameter table and factory. The command line builds its
// --method choices, its flags and its --help groups from it, and
// docs/cli.md's method tables are generated from it (tests/cli_test.sh checks they agree).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/image.h"
#include "raytrace/ray_tracer.h"
#include "render/driver.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "util/parameters.h"

namespace radiant {

/// What a method that owns its loop (multipass) is given: the image to make,
/// the command line's sampling settings and how to solve and write. Its
/// passes write their images through `output` as they complete.
struct ImageJob {
  const RayTracer &tracer;
  const PinholeCamera &camera;
  int width = 0, height = 0;
  double pixelAngle = 0;  ///< the angle one pixel subtends, radians (texturePixelSpread)
  int samplesPerPixel = 64;
  double timeBudgetSeconds = 0;  ///< 0: none
  uint64_t seed = 1;
  int threads = 0;
  /// A radiosity solution: `maxShots` > 0, a progressive solution interrupted
  /// after that many shots (a preview); 0, the solution the command line asks for.
  std::function<Solution(int maxShots)> solve;
  /// One completed pass: its number (1, 2, …), a line saying what it did,
  /// and its image and the variance of each pixel's mean.
  std::function<void(int pass, const std::string &summary, const Image &mean, const Image &variance)> output;
  /// A progress reporter for a pass's label (render/driver.h), or none.
  std::function<ProgressCallback(const std::string &label)> progress;
  /// --checkpoint: where the method saves its state (its own format), the
  /// job it belongs to, how often, and whether to carry on from it; empty: never.
  std::string checkpointPath, checkpointJob;
  double checkpointIntervalSeconds = 10;
  bool resume = false;
};

/// A registry entry: one rendering method. Most methods work at
/// the level of a camera ray (`create`: the driver owns tiles, threads and
/// sample counts); a method that owns its loop (multipass: passes, several
/// films, outputs as it goes) gives `render` instead (pbrt-v4's Integrator
/// against RayIntegrator).
struct RendererInfo {
  const char *name;
  const char *summary;
  ParameterTable parameters;  ///< its own parameters, defaults and ranges (util/parameters.h)
  std::unique_ptr<Renderer> (*create)(const RayTracer &, const RenderContext &, const Parameters &) = nullptr;
  void (*render)(const ImageJob &, const Parameters &) = nullptr;
  bool needsSolution = false;       ///< the driver must solve (or load) radiosity first
  bool supportsIrradiance = false;  ///< honours RenderContext::irradiance
  /// Samples per pixel when neither --spp nor --time is given, if more than
  /// the scene's render.spp (0: the scene's). For the radiosity displays,
  /// whose samples only antialias (one ray each; a smooth pixel stops after
  /// 8): the edges, a light's outline above all, need hundreds.
  int defaultSamplesPerPixel = 0;
};

/// Every rendering method, by name (render/registry.cpp).
const std::vector<RendererInfo> &rendererRegistry();
/// The registry entry for `name`; throws InputError (the parameter "method") listing the known names.
const RendererInfo &findRenderer(const std::string &name);
/// Checks `given` against the method's table (unknown or misplaced parameters,
/// types, ranges; util/parameters.h) and returns its view of them.
Parameters methodParameters(const RendererInfo &method, const ParameterValues &given);
/// A ray-level method by name, with its parameters checked (throws InputError).
std::unique_ptr<Renderer> createRenderer(const std::string &name, const RayTracer &tracer, const RenderContext &context,
                                         const ParameterValues &given = {});

}  // namespace radiant
