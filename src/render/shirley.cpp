// `shirley` and `kok` — direct light per pixel, indirect light from the
// solution (C&W §9.3.1).
//
// `shirley` (Shirley, Graphics Interface 1990; C&W §9.3.1): at the
// visible point x, direct light is re-evaluated by Monte Carlo sampling of
// the emitters (one shadow ray per camera sample), and the indirect light is
// interpolated from the solution's separately stored *indirect* radiosity —
// what arrived after at least one reflection (plus progressive refinement's
// ambient term, less the first arrival of any emission not yet shot, which
// the emitter samples already count). The solution's
// direct part is never read, so L D E paths come only from the shadow rays
// and L D D+ E paths only from the solution.
//
// `kok` (Kok & Jansen 1991; C&W §9.3.1): as shirley, and the patches that
// reflect the most power are sampled per pixel too, like emitters, reading
// their reflected radiosity (B − E). Their share of the indirect radiosity,
// computed per element with the same values (render/secondary_sources.h), is
// subtracted before interpolation, so what the shadow rays add is not also
// read from the solution.
//
// Caustics (L S+ D E) are not represented (unless multipass gives a caustic map, RenderContext::caustics): the
// solution holds diffuse transport only and shadow rays stop at glass (issue: multi-pass method).
#include <optional>

#include "radiosity/solution_query.h"
#include "render/bump_gather.h"
#include "render/caustic_photons.h"
#include "render/registry.h"
#include "render/secondary_sources.h"
#include "render/two_pass.h"
#include "util/sampling.h"

namespace radiant {

namespace {

class DirectPlusInterpolatedIndirect final : public TwoPassRenderer {
 public:
  /// `sources`: kok's secondary sources, or none (shirley).
  DirectPlusInterpolatedIndirect(const RayTracer &tracer, const RenderContext &context,
                                 const SelectiveOptions &selective, int bumpOrientations,
                                 const std::optional<SecondarySourceOptions> &sources)
      : TwoPassRenderer(tracer, context, selective) {
    const Solution &s = solution_;
    remainingIndirect_ = nodeField(s, Field::Indirect);
    if (sources) {
      sources_.emplace(tracer, s, *sources);
      const std::vector<Bands> removed = s.nodeValues(sources_->removedRadiosity());
      for (size_t v = 0; v < remainingIndirect_.size(); ++v) remainingIndirect_[v] = remainingIndirect_[v] - removed[v];
    }
    // Bump maps: the interpolated indirect light, seen by a tilted normal (Chen's ratio of reflected light).
    BumpGatherOptions bump;
    bump.orientations = bumpOrientations;
    bump.reflectedOnly = true;
    bumps_.emplace(tracer, s, bump);
    if (bumps_->empty()) bumps_.reset();
    prepareExactDirectLight();  // exact per pixel where it applies (two_pass.h), sampled elsewhere
  }

 protected:
  Bands reflected(const VisiblePoint &x, Sampler &rng) const override {
    const std::optional<Bands> exact = exactDirectLight(x);
    Bands L = exact ? *exact : directLight(x, rng);
    if (sources_) L += secondaryLight(x, rng);
    // The indirect field with eq. 9.11 at x (radiosity/solution_query.h), and Chen's ratio on a bump map.
    Bands indirect = fieldRadiance(solution_, remainingIndirect_, x.at);
    if (bumps_ && x.at.scaled) indirect *= bumps_->ratio(x.at.location, x.hit.shadingNormal, x.unbumpedNormal);
    // Multipass: caustics from the light-ray pass (the solution holds none; shadow rays cannot find them).
    if (context_.caustics)
      L += context_.caustics->reflectedRadiance(x.hit.position, x.hit.geometricNormal, x.reflectance);
    return L + indirect;
  }

 private:
  /// Light reflected by the selected secondary sources, by two strategies
  /// combined with the power heuristic (Veach 1997 ch. 9): a point on a
  /// source (good far away) and a cosine-distributed ray (good close by,
  /// where 1/r² of a nearby large reflector would otherwise give fireflies).
  Bands secondaryLight(const VisiblePoint &x, Sampler &rng) const {
    const Vec3 &n = x.hit.shadingNormal;
    const Bands f = x.reflectance * kInvPi;  // the solution holds only the diffuse part of x's reflection
    if (f.max() <= 0) return Bands(0.0);
    Bands L(0.0);

    SecondarySourceSample source;
    double uSelect = rng.next(), u1 = rng.next(), u2 = rng.next();
    if (sources_->sample(uSelect, u1, u2, source)) {
      Vec3 toSource = source.position - x.hit.position;
      double distance2 = dot(toSource, toSource);
      Vec3 wi = toSource / std::sqrt(std::max(distance2, 1e-300));
      double cosSource = -dot(wi, source.normal), cosSurface = dot(wi, n);
      if (distance2 > 0 && cosSource > 0 && cosSurface > 0 && dot(wi, x.hit.geometricNormal) > 0 &&
          tracer_.visible(x.hit.position, x.hit.geometricNormal, source.position, source.normal)) {
        double pdfSource = source.pdfArea * distance2 / cosSource, pdfCosine = cosSurface * kInvPi;
        L += f * source.radiance * (cosSurface / pdfSource * powerHeuristic(pdfSource, pdfCosine));
      }
    }

    double v1 = rng.next(), v2 = rng.next();
    Vec3 wi = Frame::fromNormal(n).toWorld(sampleCosineHemisphere(v1, v2));
    if (dot(wi, x.hit.geometricNormal) <= 0) return L;
    Hit y;
    SolutionPoint at;
    if (!tracer_.intersect(tracer_.spawnRay(x.hit.position, x.hit.geometricNormal, wi), y)) return L;
    if (!locateHit(solution_, y, -wi, at)) return L;  // the back of a face, or no patch
    // The density with which sample() picks y: that of y's own patch (a face
    // cut where other surfaces meet it has several, each selected or not).
    double pdfArea = sources_->pdfArea(solution_.mesh.elements[at.location.element].patch);
    if (pdfArea <= 0) return L;
    double pdfSource = pdfArea * y.distance * y.distance / -dot(wi, y.geometricNormal);
    double pdfCosine = dot(wi, n) * kInvPi;
    Bands radiance = sources_->radiance(at.location.element);
    return L + x.reflectance * radiance * powerHeuristic(pdfCosine, pdfSource);  // f·cos/pdf = ρ
  }

  std::optional<SecondarySources> sources_;
  std::vector<Bands> remainingIndirect_;  ///< node values of indirect − removed
  std::optional<BumpGather> bumps_;       ///< bump-mapped patches only
};

std::unique_ptr<Renderer> createShirley(const RayTracer &tracer, const RenderContext &context,
                                        const Parameters &parameters) {
  return std::make_unique<DirectPlusInterpolatedIndirect>(tracer, context, SelectiveOptions::from(parameters),
                                                          bumpOrientations(parameters), std::nullopt);
}

std::unique_ptr<Renderer> createKok(const RayTracer &tracer, const RenderContext &context,
                                    const Parameters &parameters) {
  return std::make_unique<DirectPlusInterpolatedIndirect>(tracer, context, SelectiveOptions::from(parameters),
                                                          bumpOrientations(parameters),
                                                          SecondarySourceOptions::from(parameters));
}

}  // namespace

RendererInfo shirleyMethod() {
  ParameterTable parameters = {bumpOrientationsParameter()};
  for (const ParameterSpec &spec : selectiveParameters()) parameters.push_back(spec);
  return {"shirley",  "direct light per pixel, indirect interpolated from the solution",
          parameters, &createShirley,
          nullptr,    true};
}

RendererInfo kokMethod() {
  ParameterTable parameters = secondarySourceParameters();
  parameters.push_back(bumpOrientationsParameter());
  for (const ParameterSpec &spec : selectiveParameters()) parameters.push_back(spec);
  return {"kok",      "as shirley, plus the brightest reflectors sampled per pixel like emitters (Kok & Jansen 1991)",
          parameters, &createKok,
          nullptr,    true};
}

}  // namespace radiant
