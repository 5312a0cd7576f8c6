// Picks points on emitters for next-event estimation.
//
// Emissive triangles are chosen in proportion to their power
// Φ = π·A·L̄ (one-sided Lambertian emitter of radiance L, averaged over bands),
// then a point uniformly on the chosen triangle. The density of a point is
// therefore p(triangle)/A per unit area, whichever band is being estimated.
// Point lights (scene/light.h) join the same choice with their flux Φ̄; a
// point light is a delta in position: no continuation can hit it, so its
// estimate is I(ω)·cos θ / (d² p(light)), weighted 1 (Veach 1997, §9.2.4).
//
// estimateDirectLight is the one next-event estimate of every method that
// samples the emitters at a surface point (path, and the two-pass methods
// rushmeier, shirley and kok): one point on an emitter, one shadow ray.
#pragma once

#include <vector>

#include "raytrace/ray_tracer.h"
#include "render/bsdf.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace radiant {

struct LightSample {
  Vec3 position;
  Vec3 normal;         ///< the emitter's front side
  Bands radiance;      ///< emitted radiance towards the front, W·sr⁻¹·m⁻²
  double pdfArea = 0;  ///< density per unit area, m⁻²
  uint32_t triangle = 0;
  /// Set when a point light was chosen (position is its position; normal,
  /// radiance, pdfArea and triangle are then unused): `probability` is the
  /// chance of choosing it.
  const PointLight *pointLight = nullptr;
  double probability = 0;
};

class LightSampler {
 public:
  explicit LightSampler(const Scene &scene);

  bool empty() const { return cumulative_.empty(); }
  /// Total emitted power, W (per band).
  const Bands &totalPower() const { return totalPower_; }
  bool sample(double uSelect, double u1, double u2, LightSample &out) const;
  /// Area density of sample() producing a point on `triangle` (0 for non-emitters).
  double pdfArea(uint32_t triangle) const;

  /// Probability of choosing each emitter (for tests); the point lights
  /// follow the emitting triangles, at emitterCount() … emitterCount() + pointLightCount() − 1.
  double selectionProbability(size_t emitterIndex) const { return probability_[emitterIndex]; }
  size_t emitterCount() const { return emitters_.size(); }
  uint32_t emitterTriangle(size_t emitterIndex) const { return emitters_[emitterIndex]; }
  size_t pointLightCount() const { return scene_.lights.size(); }

 private:
  const Scene &scene_;
  std::vector<uint32_t> emitters_;         ///< triangle indices
  std::vector<double> cumulative_;         ///< CDF over emitters_, then the scene's point lights
  std::vector<double> probability_;        ///< per emitter
  std::vector<double> pdfAreaByTriangle_;  ///< per scene triangle
  Bands totalPower_;
};

/// Irradiance at a surface point from every point light (Scene::lights) it
/// sees, exactly: Σ I(ω) cos θ / d² with cos θ against the shading normal and
/// one shadow ray per light (the per-pixel gather of reichert).
Bands pointLightIrradiance(const RayTracer &tracer, const Hit &hit);

/// How a next-event estimate is weighted.
enum class LightWeighting {
  /// Alone: nothing else finds the emitters (the two-pass methods), so the
  /// estimate is the plain f·L·cosθ·cosθ_l / (r² p_A).
  Alone,
  /// Against a BSDF-sampled continuation that also finds them (the path
  /// tracer): the power heuristic with β = 2 (Veach 1997, ch. 9).
  PowerHeuristic,
};

/// Next-event estimate of the direct light a surface point reflects towards
/// the BSDF's outgoing direction: a point on an emitter chosen by power
/// (three numbers from rng), its front side only (emitters are one-sided),
/// the BSDF, one shadow ray. 0 where the sample is behind the emitter,
/// outside the BSDF's support, or occluded.
Bands estimateDirectLight(const LightSampler &lights, const RayTracer &tracer, const Hit &hit, const Bsdf &bsdf,
                          Sampler &rng, LightWeighting weighting);

}  // namespace radiant
