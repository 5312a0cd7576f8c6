// What the two-pass methods of C&W §9.3 share (rushmeier, reichert, shirley,
// kok): a first-pass radiosity solution is trusted for light arriving from
// far away, and part of the transport is recomputed at each pixel's visible
// point x. The base class finds x through mirrors and glass, adds x's own
// emission, applies selective re-evaluation, and leaves to each method only
// the light x reflects towards the eye.
//
// Light paths are partitioned (Heckbert's regular-expression notation, SIGGRAPH 1990; docs/two-pass.md) so each is
// counted once: whatever a method samples per pixel, it removes from what it
// reads from the solution.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "radiosity/backprojection.h"
#include "radiosity/solution_query.h"
#include "render/light_sampler.h"
#include "render/renderer.h"
#include "util/parameters.h"

namespace radiant {

/// The diffuse (non-delta) point a camera ray reaches after ideal specular
/// bounces, and what it needs to be shaded.
struct VisiblePoint {
  Hit hit;
  Vec3 wo;                ///< towards the viewer
  Bands throughput{1.0};  ///< product of the specular bounces' weights
  int specularBounces = 0;
  /// Where the solution is read (radiosity/solution_query.h): the mesh
  /// location, and with surface detail (`at.scaled`) eq. 9.11's ρ(x)/ρ̄(x).
  SolutionPoint at;
  const Material *material = nullptr;
  /// Surface detail (raytrace/surface_detail.h): ρ(x), the diffuse reflectance
  /// here (the material's, times its texture), and hit.shadingNormal is the
  /// bumped normal.
  Bands reflectance;
  Vec3 unbumpedNormal;  ///< the shading normal before the bump or normal map (smooth shading included)
};

/// Follows a ray through ideal mirrors and glass (Fresnel-weighted choice, as
/// the path tracer does) to the first non-delta surface. False if it escapes,
/// is absorbed, or reaches a point the solution does not hold (locateHit:
/// the back of a face, a face outside the mesh): those are black.
/// `pixelSpread`: the angle one pixel subtends (radians), which sets the width
/// of the texture filter at x (0: the finest texels). `reconstruction`: how
/// the solution will be read at x (the texture factor's ρ̄ follows it).
bool findVisiblePoint(const RayTracer &tracer, const Solution &solution, Ray ray, Sampler &rng, VisiblePoint &out,
                      double pixelSpread = 0, Reconstruction reconstruction = Reconstruction::Interpolated);

/// --selective (C&W §9.3.3): what the two-pass methods share of their
/// parameters; reichert adds selective-power for its link mode.
struct SelectiveOptions {
  bool enabled = false;
  double threshold = 0;  ///< element mode: re-evaluate where the element's error estimate exceeds this
  double linkPower = 0;  ///< link mode: partially visible links carrying at least this fraction of the emitted power
  static SelectiveOptions from(const Parameters &parameters);
};
/// selective and selective-threshold (every two-pass method's parameters).
const ParameterTable &selectiveParameters();
/// selective-power (reichert's link mode).
const ParameterSpec &selectivePowerParameter();

class TwoPassRenderer : public Renderer {
 public:
  TwoPassRenderer(const RayTracer &tracer, const RenderContext &context, const SelectiveOptions &selective);

  Bands radiance(const Ray &ray, Sampler &rng) const final;
  /// With selective: the channel "selective-elements" (1 where the sample was
  /// re-evaluated, 0 where it read the solution) or, in link mode,
  /// "selective-links" (how many links it re-evaluated): --selective-map.
  std::vector<std::string> channels() const final;
  Bands sample(const Ray &ray, Sampler &rng, Bands *values) const final;

  /// How much per-pixel work a camera ray triggers — 1 or 0 (element mode)
  /// or the number of links re-evaluated (link mode); 0 without selective.
  virtual double selectiveWork(const Ray &ray) const;
  bool selectsByLinks() const { return selectsByLinks_; }

 protected:
  /// Radiance x reflects towards the eye (its own emission is added by the caller).
  virtual Bands reflected(const VisiblePoint &x, Sampler &rng) const = 0;
  /// Link mode (--selective with a hierarchical solution): radiance reflected
  /// at x, re-evaluating only the significant partially visible links. Only
  /// methods that set selectsByLinks_ implement it.
  virtual Bands reflectedByLinks(const VisiblePoint &x, Sampler &rng) const;

  /// Direct light by next-event estimation (estimateDirectLight, alone:
  /// nothing else in these methods finds emitters).
  Bands directLight(const VisiblePoint &x, Sampler &rng) const;
  /// True where --selective leaves the solution alone (element error below threshold).
  bool trustsSolution(const VisiblePoint &x) const;

  /// Sets up exact direct light (backprojection: the visible part of each
  /// emitter by Lambert's contour integral, radiosity/backprojection.h) when
  /// the scene has at most kMaxExactEmitters emitting faces, for its cost:
  /// one pass over them per sample.
  void prepareExactDirectLight();
  /// ρ/π times the exact irradiance, plus through a translucent face τ/π
  /// times the other side's; nothing without prepareExactDirectLight, at a
  /// point that is not Lambertian or whose shading normal is not its
  /// geometric one (a bump or smooth normal tilts the cosine away from what
  /// the contour integral takes), or where a shaft to an emitter holds more
  /// than kMaxExactOccluders faces (a tessellated model in the way: the
  /// shadow ray is cheaper than subtracting them all).
  std::optional<Bands> exactDirectLight(const VisiblePoint &x) const;
  static constexpr size_t kMaxExactEmitters = 64;
  static constexpr size_t kMaxExactOccluders = 32;

  const RayTracer &tracer_;
  const Scene &scene_;
  const Solution &solution_;
  const RenderContext context_;
  const SelectiveOptions selective_;
  LightSampler lights_;
  bool selectsByLinks_ = false;

 private:
  std::optional<DirectIrradiance> exactDirect_;  ///< after prepareExactDirectLight, with few emitting faces
};

/// The context's solution, or an InputError: the method needs one.
const Solution &requireSolution(const RenderContext &context);

}  // namespace radiant
