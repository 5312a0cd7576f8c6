// `reichert` — form factors per pixel to every element (Reichert 1992,
// "A two-pass radiosity method driven by lights and viewer position";
// C&W §9.3.1).
//
// At the visible point x the irradiance is gathered from the whole mesh:
//   L(x) = Le(x) + (ρ/π) Σ_j F(dx → A_j) V(x, A_j) B_j
// with F the exact unoccluded point-to-polygon factor (Lambert's contour
// integral, C&W ch. 4) and V from one shadow ray per evaluation. The sum is
// split by what the elements send, B_j = E_j + (B_j − E_j), each part
// counted once:
//   - their emission E_j, every sample: the visible part of each emitter
//     exactly (backprojection, --emitters exact, where it applies: two_pass.h)
//     or, elsewhere and with --emitters gather, through the emitters' own cut
//     as below; point lights, which are not elements, add I cos θ / d² each;
//   - their reflected radiosity B_j − E_j, through a cut of the reflecting
//     elements' tree (render/source_tree.h), not over every element: near,
//     bright and large sources down to their elements, far and dim ones as
//     whole nodes, each node estimated from one of its elements drawn by
//     importance and weighted by the inverse of that chance — an unbiased
//     estimate of the whole sum, whose cost follows the cut (at most
//     max-cut nodes), not the element count. cut-error 0 takes every element.
// The reflected part is the costly one (hundreds of form factors and
// shadow rays) and the smooth one, which the solution already holds: each
// sample reads the solution's interpolated indirect radiance, and a random
// fraction q of them (--gather-chance) add (gather − solution) / q. The mean
// is the gather's, whatever the solution's error (a control variate, with
// Russian roulette on the correction); the cost is q gathers a sample, so
// many more samples cover each pixel's edges and shadows at the same time.
// The two variants of the book:
//   --ff point  visibility to the element's centre, and each node read
//               through the same element at every pixel: a shadow boundary
//               shows the mesh's coherent stair-steps;
//   --ff mc     a uniformly random point of a randomly drawn element: the
//               same errors become noise, which more samples average away.
//
// With --selective on a hierarchical solution (link mode), the gather runs
// over the links of the pixel's leaf and its ancestors instead: the
// partially visible links that carry much power are re-evaluated at the
// pixel (F(dx → source) V), the rest keep the solver's value, as a
// correction to the interpolated radiosity:
//   B(x) = B_interp(x) + ρ Σ_{re-evaluated links} (F(dx → s) V − F_link) B_s
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "radiosity/form_factor.h"
#include "render/light_sampler.h"
#include "render/registry.h"
#include "render/source_tree.h"
#include "render/two_pass.h"
#include "util/error.h"

namespace radiant {

namespace {

/// Each element's own reflected radiosity (radiosity/solution_query.h: B_j − E_j as displayed, at least zero).
std::vector<Bands> reflectedRadiosities(const Solution &solution) {
  std::vector<Bands> reflected(solution.elementCount());
  for (uint32_t e = 0; e < reflected.size(); ++e) reflected[e] = reflectedRadiosity(solution, e);
  return reflected;
}

class Reichert final : public TwoPassRenderer {
 public:
  Reichert(const RayTracer &tracer, const RenderContext &context, const SelectiveOptions &selective, bool pointSampled,
           bool exactDirect, double cutError, int maxCut, double gatherChance)
      : TwoPassRenderer(tracer, context, selective),
        pointSampled_(pointSampled),
        cutError_(cutError),
        maxCut_(maxCut),
        gatherChance_(gatherChance),
        reflectedRadiosity_(reflectedRadiosities(solution_)),
        emitters_(solution_.mesh, solution_.emission),
        reflectors_(solution_.mesh, reflectedRadiosity_),
        indirect_(nodeField(solution_, Field::Indirect)) {
    if (exactDirect) prepareExactDirectLight();
    const RadiosityMesh &mesh = solution_.mesh;
    polygons_.resize(mesh.elements.size());
    for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
      std::vector<Vec3> p = mesh.polygon(e);
      std::copy(p.begin(), p.end(), polygons_[e].begin());
    }
    if (selective_.enabled && isHierarchical(solution_)) {
      // Link mode: only the partially visible links that carry much power are re-evaluated per pixel.
      selectsByLinks_ = true;
      const double powerFloor = selective_.linkPower * solution_.stats.emittedPower.average();
      links_ = indexLinksByReceiver(solution_, [&](const Link &link) {
        return link.visibility == LinkVisibility::Partial && link.carriedPower >= powerFloor;
      });
    }
  }

  double selectiveWork(const Ray &ray) const override {
    if (!selectsByLinks_) return TwoPassRenderer::selectiveWork(ray);
    Sampler rng{Pcg32()};
    VisiblePoint x;
    if (!findVisiblePoint(tracer_, solution_, ray, rng, x)) return 0;
    int count = 0;
    forEachLinkLighting(solution_, links_, x.at.location.element, [&](const Link &) { ++count; });
    return count;
  }

 protected:
  Bands reflected(const VisiblePoint &x, Sampler &rng) const override {
    // Draw the gather's number first, so the random sequence does not depend on what the emitters take.
    const double uGather = rng.next();
    const std::optional<Bands> exact = exactDirectLight(x);
    const Bands emitted = exact ? *exact : gathered(x, emitters_, solution_.emission, true, rng);
    if (gatherChance_ >= 1) return emitted + gathered(x, reflectors_, reflectedRadiosity_, false, rng);
    // The solution's light after one or more reflections, with eq. 9.11 at x (radiosity/solution_query.h).
    const Bands fromSolution = fieldRadiance(solution_, indirect_, x.at);
    if (uGather >= gatherChance_) return emitted + fromSolution;
    const Bands reflectedLight = gathered(x, reflectors_, reflectedRadiosity_, false, rng);
    return emitted + fromSolution + (reflectedLight - fromSolution) / gatherChance_;
  }

  /// The radiance x reflects from `sources` (their elements sending
  /// `radiosity`): ρ(x)/π times the irradiance they give, and through a
  /// translucent face τ/π times the other side's; with the point lights.
  Bands gathered(const VisiblePoint &x, const SourceTree &sources, const std::vector<Bands> &radiosity,
                 bool withPointLights, Sampler &rng) const {
    // ρ(x): a texture is applied directly.
    Bands L = x.reflectance * irradianceAt(x.hit, sources, radiosity, withPointLights, rng);
    const Material &material = tracer_.scene().materials[x.hit.material];
    if (material.isTranslucent()) {
      Hit behind = x.hit;
      behind.geometricNormal = -behind.geometricNormal, behind.shadingNormal = -behind.shadingNormal;
      L += material.transmittance * irradianceAt(behind, sources, radiosity, withPointLights, rng);
    }
    return L * kInvPi;
  }

  /// The irradiance at a surface point, on the side its normals face: the
  /// cut's F(dx → A_j) V B_j, each over its chance, plus the point lights.
  Bands irradianceAt(const Hit &hit, const SourceTree &sources, const std::vector<Bands> &radiosity,
                     bool withPointLights, Sampler &rng) const {
    const RadiosityMesh &mesh = solution_.mesh;
    Bands irradiance(0.0);
    thread_local std::vector<SourceTree::CutNode> cut;
    sources.chooseCut(hit.position, hit.shadingNormal, cutError_, maxCut_, cut);
    for (const SourceTree::CutNode &node : cut) {
      // Draw the numbers first, so the random sequence does not depend on geometry.
      const double u0 = rng.next(), u1 = rng.next(), u2 = rng.next();
      // --ff point reads each node through one element, the same at every pixel (a fixed golden-ratio draw).
      const double pick = pointSampled_ ? std::fmod(0.5 + 0.6180339887498949 * node.node, 1.0) : u0;
      double probability = 1;
      const uint32_t j = sources.drawElement(node.node, hit.position, hit.shadingNormal, pick, probability);
      const Element &element = mesh.elements[j];
      const Vec3 &nj = mesh.normalOf(j);
      if (dot(hit.position - element.centre, nj) <= 0) continue;  // x is behind j: j's front faces away
      const double f = visibleFormFactor(hit, {polygons_[j].data(), size_t(element.vertexCount)}, nj, u1, u2);
      if (f > 0) irradiance += radiosity[j] * (f / probability);
    }
    // Point lights are no elements: their light is gathered the same way, exactly.
    if (withPointLights && !tracer_.scene().lights.empty()) irradiance += pointLightIrradiance(tracer_, hit);
    return irradiance;
  }

  Bands reflectedByLinks(const VisiblePoint &x, Sampler &rng) const override {
    const RadiosityMesh &mesh = solution_.mesh;
    Bands correction(0.0);
    forEachLinkLighting(solution_, links_, x.at.location.element, [&](const Link &link) {
      const MeshTreeNode &source = mesh.tree[link.source];
      double u1 = rng.next(), u2 = rng.next();
      const Vec3 &ns = mesh.patches[source.patch].normal;
      Vec3 centre{};
      for (int k = 0; k < source.vertexCount; ++k) centre += source.corners[k] / double(source.vertexCount);
      double f = dot(x.hit.position - centre, ns) > 0
                     ? visibleFormFactor(x.hit, {source.corners.data(), size_t(source.vertexCount)}, ns, u1, u2)
                     : 0.0;
      correction += solution_.treeRadiosity[link.source] * (f - link.formFactor);
    });
    return (reflectedRadiosity(solution_, x.at) + x.reflectance * correction) * kInvPi;
  }

 private:
  /// F(dx → polygon) × V (radiosity/form_factor.h), visibility tested at
  /// one point of the polygon's part in front of x: its centroid (--ff
  /// point) or a uniform one from (u1, u2) (--ff mc).
  double visibleFormFactor(const Hit &x, std::span<const Vec3> polygon, const Vec3 &polygonNormal, double u1,
                           double u2) const {
    VisibilitySamples samples;
    samples.centroid = pointSampled_, samples.u1 = u1, samples.u2 = u2;
    return radiant::visibleFormFactor(tracer_, x.position, x.shadingNormal, x.geometricNormal, polygon, polygonNormal,
                                      samples);
  }

  const bool pointSampled_;
  const double cutError_;
  const int maxCut_;
  const double gatherChance_;  ///< q: the chance that a sample gathers the reflected light (1: every one)
  const std::vector<Bands> reflectedRadiosity_;  ///< B_j − E_j per element, ambient included (as displayed)
  const SourceTree emitters_;                    ///< the elements of positive E_j
  const SourceTree reflectors_;                  ///< the elements of positive B_j − E_j
  const std::vector<Bands> indirect_;            ///< node values of the solution's light after a reflection
  std::vector<std::array<Vec3, 4>> polygons_;
  LinksByReceiver links_;  ///< link mode: the selected links by receiver tree node
};

std::unique_ptr<Renderer> createReichert(const RayTracer &tracer, const RenderContext &context,
                                         const Parameters &parameters) {
  SelectiveOptions selective = SelectiveOptions::from(parameters);
  selective.linkPower = parameters.real("selective-power");
  return std::make_unique<Reichert>(tracer, context, selective, parameters.choice("ff") == "point",
                                    parameters.choice("emitters") == "exact", parameters.real("cut-error"),
                                    int(parameters.integer("max-cut")), parameters.real("gather-chance"));
}

}  // namespace

RendererInfo reichertMethod() {
  ParameterTable parameters = {
      {"ff",
       ParameterType::Choice,
       "mc",
       "visibility of each per-pixel form factor from one shadow ray to the element's centre (point: coherent "
       "stair-steps at shadow edges) or to a random point of it (mc: noise that samples average away)",
       0,
       0,
       {"point", "mc"}},
      {"emitters",
       ParameterType::Choice,
       "exact",
       "the emitters' light: the visible part of each exactly, by backprojection (at most 64 emitting faces, a "
       "Lambertian point without bump or smooth normal, few faces in the way; elsewhere as gather), or gather: "
       "through their cut like the other elements, visibility as --ff",
       0,
       0,
       {"exact", "gather"}},
      {"cut-error", ParameterType::Real, "0.02",
       "the gather's cut of the elements' tree is split while a node could give more than this fraction of the "
       "point's irradiance (Walter et al.'s lightcuts bound); 0: every element, the exact sum (slow on large meshes)",
       0, 1},
      {"max-cut", ParameterType::Integer, "256",
       "at most this many nodes in a point's cut (each one form factor and one shadow ray)", 1, 1 << 20},
      {"gather-chance", ParameterType::Real, "0.02",
       "the chance that a sample gathers the reflected light; the others read the solution's interpolated "
       "indirect light, which the gathering ones correct, unbiased (a control variate): more samples for the "
       "pixel's edges at the same cost; 1: every one",
       kPositive, 1}};
  for (const ParameterSpec &spec : selectiveParameters()) parameters.push_back(spec);
  parameters.push_back(selectivePowerParameter());
  return {"reichert", "form factors per pixel to every element (through a cut of their tree), ray-traced visibility",
          parameters, &createReichert,
          nullptr,    true};
}

}  // namespace radiant
