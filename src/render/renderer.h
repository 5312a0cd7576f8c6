// The one interface every rendering method implements (STYLE.md §4).
//
// A renderer estimates the radiance arriving along one camera ray; the driver
// (render/driver.h) owns tiles, threads, seeds, sample counts, time budgets,
// progress and output. A new method is one file plus one line in registry.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "raytrace/ray_tracer.h"
#include "render/sampler.h"
#include "util/spectrum.h"

namespace radiant {

class CausticPhotonMap;

/// One camera sample's estimate and, from the same random numbers, a cheaper
/// biased one of the same radiance: multipass's control variate (render/control_variate.h).
struct PairedRadiance {
  Bands radiance;  ///< unbiased
  Bands control;   ///< the path tracer: what it would give reading the solution (readSolutionDepth)
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  /// Radiance arriving at the camera along `ray`, W·sr⁻¹·m⁻² per band. Must be
  /// finite and non-negative; `rng` is this camera sample's own numbers (render/sampler.h).
  virtual Bands radiance(const Ray &ray, Sampler &rng) const = 0;
  /// The radiance and its control. A renderer without one returns the
  /// radiance as its own control (a difference of zero).
  virtual PairedRadiance pairedRadiance(const Ray &ray, Sampler &rng) const {
    const Bands L = radiance(ray, rng);
    return {L, L};
  }
  /// The estimate varies with where in its pixel the camera ray goes and
  /// hardly otherwise (the radiosity displays): a pixel whose samples
  /// agree has converged, and the driver spends no more on it.
  virtual bool variesOnlyAcrossThePixel() const { return false; }
};

struct Solution;

/// Options shared by the renderers, from the command line and scene file.
struct RendererOptions {
  int maxDepth = 0;  ///< 0: unlimited, Russian roulette ends paths
  /// Estimate irradiance instead of radiance (render --quantity irradiance):
  /// W·m⁻² arriving at the front of the first non-specular surface seen
  /// (through mirrors and glass), its own emission left out — what a lux
  /// meter lying on it reads, for false-colour illuminance maps. `path`,
  /// `flat` and `interpolate` only (supportsIrradiance).
  bool irradiance = false;
  /// The angle one pixel subtends, radians: texture maps are filtered over
  /// the pixel's footprint where a camera ray meets them (0: finest texels).
  /// texturePixelSpread gives the value the command line uses.
  double pixelSpreadAngle = 0;
  /// interpolate: normal orientations gathered per node of a bump-mapped patch (render/bump_gather.h).
  int bumpOrientations = 16;

  // Multipass (render/multipass.h).
  /// Caustics (L S+ D) from light-ray tracing, added at non-specular points by
  /// path, shirley and kok; emission reached from such a point through
  /// specular bounces is then left out. nullptr: none.
  const CausticPhotonMap *caustics = nullptr;
  /// path with a solution: at the (d+1)-th non-specular vertex, read the
  /// solution's reflected radiosity instead of continuing (pairedRadiance:
  /// that reading is the control, and the path goes on); 0: never.
  int readSolutionDepth = 0;
  /// The radiosity solution, for the methods that read one (it must outlive the renderer).
  const Solution *solution = nullptr;

  // The two-pass methods (render/two_pass.h, docs/two-pass.md).
  /// reichert: visibility of each per-pixel form factor sampled at the
  /// element's centre ("point": coherent patterns) or at a random point ("mc": noise).
  std::string formFactorSampling = "mc";
  /// kok: how many patches to sample as secondary sources, by reflected power…
  int secondarySources = 4;
  /// …or, when > 0, the fewest patches carrying this fraction of the reflected power.
  double secondarySourceFraction = 0;
  /// kok: the visibility of each removed form factor, from grid × grid points
  /// on the source element (multipass's pass 2 takes 1: its image is a preview).
  int removalVisibilityGrid = 2;
  /// Re-evaluate per pixel only where the solution is flagged inaccurate.
  bool selective = false;
  /// Element mode: re-evaluate where the element's error estimate exceeds this.
  double selectiveThreshold = 0.1;
  /// Link mode (reichert on a hierarchical solution): re-evaluate the partially
  /// visible links carrying at least this fraction of the emitted power.
  double selectiveLinkPower = 1e-4;
};

/// The texture filter width for `samplesPerPixel` samples: the pixel's angle
/// shared among its samples (pbrt scales ray differentials by max(1/8, 1/√spp)).
inline double texturePixelSpread(const CameraSettings &camera, int height, int samplesPerPixel) {
  return pixelAngle(camera, height) * std::max(0.125, 1 / std::sqrt(double(std::max(1, samplesPerPixel))));
}

struct RendererInfo {
  const char *name;
  const char *summary;
  std::unique_ptr<Renderer> (*create)(const RayTracer &, const RendererOptions &);
  bool needsSolution = false;       ///< the driver must solve (or load) radiosity first
  bool supportsIrradiance = false;  ///< honours RendererOptions::irradiance
};

/// Every rendering method, by name (render/registry.cpp).
const std::vector<RendererInfo> &rendererRegistry();
/// The registry entry for `name`; throws InputError listing the known names.
const RendererInfo &findRenderer(const std::string &name);
/// Throws InputError listing the known names for an unknown one.
std::unique_ptr<Renderer> createRenderer(const std::string &name, const RayTracer &tracer,
                                         const RendererOptions &options);

}  // namespace radiant
