// The one interface every rendering method implements.
//
// A renderer estimates the radiance arriving along one camera ray; the driver
// (render/driver.h) owns tiles, threads, seeds, sample counts, time budgets,
// progress and output. A new method is one file plus one line in registry.cpp
// (render/registry.h; docs/adding-a-method.md).
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

class Renderer {
 public:
  virtual ~Renderer() = default;
  /// Radiance arriving at the camera along `ray`, W·sr⁻¹·m⁻² per band. Must be
  /// finite and non-negative; `rng` is this camera sample's own numbers (render/sampler.h).
  virtual Bands radiance(const Ray &ray, Sampler &rng) const = 0;
  /// The extra per-sample outputs it can give, by name (film channels,
  /// render/film.h): "control" (path reading a solution: the estimate that
  /// reads it where the path goes on, multipass's control variate),
  /// "selective-elements" or "selective-links" (the two-pass methods with
  /// selective: the work a sample triggered). None by default.
  virtual std::vector<std::string> channels() const { return {}; }
  /// One sample's radiance and, in `values` (one per name of channels(), in
  /// that order), its extra outputs from the same numbers.
  virtual Bands sample(const Ray &ray, Sampler &rng, Bands *values) const {
    (void)values;
    return radiance(ray, rng);
  }
  /// The estimate varies with where in its pixel the camera ray goes and
  /// hardly otherwise (the radiosity displays): a pixel whose samples
  /// agree has converged, and the driver spends no more on it.
  virtual bool variesOnlyAcrossThePixel() const { return false; }
};

struct Solution;

/// What every method is given besides its own parameters (RendererInfo::parameters):
/// the solution and the settings of the whole render. A method's own
/// parameters (kok's sources, reichert's form-factor sampling…) are not here:
/// each method declares them in its registry entry and reads them from Parameters.
struct RenderContext {
  /// The radiosity solution, for the methods that read one (it must outlive the renderer).
  const Solution *solution = nullptr;
  /// Estimate irradiance instead of radiance (render --quantity irradiance):
  /// W·m⁻² arriving at the front of the first non-specular surface seen
  /// (through mirrors and glass), its own emission left out — what a lux
  /// meter lying on it reads, for false-colour illuminance maps. Only the
  /// methods whose entry says supportsIrradiance.
  bool irradiance = false;
  /// The angle one pixel subtends, radians: texture maps are filtered over
  /// the pixel's footprint where a camera ray meets them (0: finest texels).
  /// texturePixelSpread gives the value the command line uses.
  double pixelSpreadAngle = 0;

  // Set by multipass (render/multipass.h) for the renderers of its passes.
  /// Caustics (L S+ D) from light-ray tracing, added at non-specular points by
  /// path, shirley and kok; emission reached from such a point through
  /// specular bounces is then left out. nullptr: none.
  const CausticPhotonMap *caustics = nullptr;
  /// path with a solution: at the (d+1)-th non-specular vertex, read the
  /// solution's reflected radiosity instead of continuing (its channel "control":
  /// that reading is the control, and the path goes on); 0: never.
  int readSolutionDepth = 0;
  /// path with readSolutionDepth: read at that vertex with the solution,
  /// instead of `caustics` (CausticPhotonMap's throughDiffuse: all the light
  /// that took a specular bounce on its way, which the solution lacks); the
  /// path that goes on past the read (the pair's P) never uses it. nullptr: `caustics`.
  const CausticPhotonMap *specularLastLight = nullptr;
};

/// The texture filter width for `samplesPerPixel` samples: the pixel's angle
/// shared among its samples (pbrt scales ray differentials by max(1/8, 1/√spp)).
inline double texturePixelSpread(double pixelAngle, int samplesPerPixel) {
  return pixelAngle * std::max(0.125, 1 / std::sqrt(double(std::max(1, samplesPerPixel))));
}
inline double texturePixelSpread(const CameraSettings &camera, int height, int samplesPerPixel) {
  return texturePixelSpread(pixelAngle(camera, height), samplesPerPixel);
}

}  // namespace radiant
