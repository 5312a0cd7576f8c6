// `flat` and `interpolate` — the radiosity solution itself, displayed (C&W §9.2).
//
// The eye ray's first diffuse hit shows the solution's radiance B/π there:
// `flat` the element's constant value (the mesh made visible), `interpolate`
// the value interpolated from the element's nodes (bilinear on quads,
// barycentric on triangles; Gouraud shading of the mesh), continuous inside a
// patch. Both include the progressive solver's ambient term. With
// RenderContext::irradiance they show the irradiance H the same way.
// Texture maps apply C&W eq. 9.11 at each pixel; bump maps, in `interpolate`,
// Chen's perturbed radiosity (render/bump_gather.h).
//
// Mirrors and glass seen from the eye are followed (ideal reflection and
// refraction, Fresnel-weighted choice) until a diffuse surface is reached,
// as the per-pixel methods do; the back side of a face, which the one-sided
// radiosity mesh does not represent, is black.

#include <optional>

#include "radiosity/solution_query.h"
#include "render/bump_gather.h"
#include "render/registry.h"
#include "render/two_pass.h"
#include "util/error.h"

namespace radiant {

namespace {

class RadiosityDisplay final : public Renderer {
 public:
  /// `bumpOrientations`: interpolate's parameter (0 for flat).
  RadiosityDisplay(const RayTracer &tracer, const Solution &solution, bool interpolate, const RenderContext &context,
                   int bumpOrientations)
      : tracer_(tracer),
        solution_(solution),
        interpolate_(interpolate),
        irradiance_(context.irradiance),
        pixelSpread_(context.pixelSpreadAngle) {
    if (interpolate_ && !irradiance_) {
      BumpGatherOptions bump;
      bump.orientations = bumpOrientations;
      bumps_.emplace(tracer, solution, bump);
      if (bumps_->empty()) bumps_.reset();
    }
    if (!irradiance_) return;
    // H per element (the ambient term arrives as irradiance too, as in the report), and at the nodes.
    for (uint32_t e = 0; e < solution.elementCount(); ++e)
      elementIrradiance_.push_back(solution.irradiance[e] + solution.ambient);
    nodeIrradiance_ = solution.nodeValues(elementIrradiance_);
  }

  Bands radiance(const Ray &cameraRay, Sampler &rng) const override {
    VisiblePoint x;
    if (!findVisiblePoint(tracer_, solution_, cameraRay, rng, x, pixelSpread_,
                          interpolate_ ? Reconstruction::Interpolated : Reconstruction::Constant))
      return Bands(0.0);
    if (irradiance_)
      return x.throughput * (interpolate_ ? solution_.interpolate(nodeIrradiance_, x.at.location)
                                          : elementIrradiance_[x.at.location.element]);
    // C&W eq. 9.11 on a texture, B = E + (B̂ − E)·ρ(x)/ρ̄, with the element's
    // own ρ̄ for flat (so an element's mean stays its B) and the interpolated
    // one for interpolate (radiosity/solution_query.h); and for a bump map,
    // Chen's ratio r(n') on the reflected part too (bump_gather.h).
    if (bumps_ && x.at.scaled)
      x.at.reflectedScale *= bumps_->ratio(x.at.location, x.hit.shadingNormal, x.unbumpedNormal);
    return x.throughput * radiosity(solution_, x.at) * kInvPi;
  }

  bool variesOnlyAcrossThePixel() const override { return true; }

 private:
  const RayTracer &tracer_;
  const Solution &solution_;
  bool interpolate_;
  bool irradiance_;
  double pixelSpread_;
  std::optional<BumpGather> bumps_;                        ///< interpolate with bump-mapped patches only
  std::vector<Bands> elementIrradiance_, nodeIrradiance_;  ///< H + ambient (irradiance only)
};

std::unique_ptr<Renderer> createFlat(const RayTracer &tracer, const RenderContext &context, const Parameters &) {
  return std::make_unique<RadiosityDisplay>(tracer, requireSolution(context), false, context, 0);
}

std::unique_ptr<Renderer> createInterpolated(const RayTracer &tracer, const RenderContext &context,
                                             const Parameters &parameters) {
  // The bumped irradiance ratio is a ratio of reflected light: an irradiance
  // image shows the unbumped irradiance arriving, and gathers nothing.
  if (context.irradiance && parameters.given("bump-orientations"))
    throw InputError(parameters.origin("bump-orientations"), "an irradiance image does not use it");
  return std::make_unique<RadiosityDisplay>(tracer, requireSolution(context), true, context,
                                            bumpOrientations(parameters));
}

}  // namespace

/// The radiosity displays' samples only antialias: their default is at
/// least this many, so that a light's outline converges (cornell-knots at
/// 256²: RMSE 0.011 at the scene's 64 spp, 0.0021 at 1024, for 2 s more).
constexpr int kDisplaySamplesPerPixel = 1024;

RendererInfo flatMethod() {
  return {"flat",  "the radiosity solution, constant per element",
          {},      &createFlat,
          nullptr, true,
          true,    kDisplaySamplesPerPixel};
}

RendererInfo interpolateMethod() {
  return {"interpolate",
          "the radiosity solution interpolated from its nodes (the classic radiosity image)",
          {bumpOrientationsParameter()},
          &createInterpolated,
          nullptr,
          true,
          true,
          kDisplaySamplesPerPixel};
}

}  // namespace radiant
