// `reichert` — form factors per pixel to every element (Reichert 1992,
// "A two-pass radiosity method driven by lights and viewer position";
// C&W §9.3.1).
//
// At the visible point x the irradiance is gathered from the whole mesh:
//   L(x) = Le(x) + (ρ/π) Σ_j F(dx → A_j) V(x, A_j) B_j
// with F the exact unoccluded point-to-polygon factor (Lambert's contour
// integral, C&W ch. 4) and V from one shadow ray per evaluation. Emitters
// are elements like any other, so direct and indirect light come from the
// same sum and nothing is counted twice; point lights, which are not
// elements, add I cos θ / d² each past one shadow ray.
//
// The sum runs over a cut of the elements' tree (render/source_tree.h), not
// over every element: near, bright and large sources down to their elements,
// far and dim ones as whole nodes, each node estimated from one of its
// elements drawn ∝ B_j A_j and weighted by the inverse of that chance — an
// unbiased estimate of the whole sum, whose cost follows the cut (at most
// max-cut nodes), not the element count. cut-error 0 takes every element.
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

#include "radiosity/form_factor.h"
#include "render/light_sampler.h"
#include "render/registry.h"
#include "render/source_tree.h"
#include "render/two_pass.h"
#include "util/error.h"

namespace radiant {

namespace {

class Reichert final : public TwoPassRenderer {
 public:
  Reichert(const RayTracer &tracer, const RenderContext &context, const SelectiveOptions &selective, bool pointSampled,
           double cutError, int maxCut)
      : TwoPassRenderer(tracer, context, selective),
        pointSampled_(pointSampled),
        cutError_(cutError),
        maxCut_(maxCut),
        sources_(solution_) {
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
    Bands radiosity = x.reflectance * irradianceAt(x.hit, rng);  // ρ(x): a texture is applied directly
    // A translucent surface passes on τ of what reaches its other side.
    const Material &material = tracer_.scene().materials[x.hit.material];
    if (material.isTranslucent()) {
      Hit behind = x.hit;
      behind.geometricNormal = -behind.geometricNormal, behind.shadingNormal = -behind.shadingNormal;
      radiosity += material.transmittance * irradianceAt(behind, rng);
    }
    return radiosity * kInvPi;
  }

  /// The irradiance at a surface point, on the side its normals face: the
  /// cut's F(dx → A_j) V B_j, each over its chance, plus the point lights.
  Bands irradianceAt(const Hit &hit, Sampler &rng) const {
    const RadiosityMesh &mesh = solution_.mesh;
    Bands irradiance(0.0);
    thread_local std::vector<SourceTree::CutNode> cut;
    sources_.chooseCut(hit.position, hit.shadingNormal, cutError_, maxCut_, cut);
    for (const SourceTree::CutNode &node : cut) {
      // Draw the numbers first, so the random sequence does not depend on geometry.
      const double u0 = rng.next(), u1 = rng.next(), u2 = rng.next();
      // --ff point reads each node through one element, the same at every pixel (a fixed golden-ratio draw).
      const double pick = pointSampled_ ? std::fmod(0.5 + 0.6180339887498949 * node.node, 1.0) : u0;
      double probability = 1;
      const uint32_t j = sources_.drawElement(node.node, hit.position, hit.shadingNormal, pick, probability);
      const Element &element = mesh.elements[j];
      const Vec3 &nj = mesh.normalOf(j);
      if (dot(hit.position - element.centre, nj) <= 0) continue;  // x is behind j: j's front faces away
      const double f = visibleFormFactor(hit, {polygons_[j].data(), size_t(element.vertexCount)}, nj, u1, u2);
      if (f > 0) irradiance += solution_.displayRadiosity(j) * (f / probability);
    }
    // Point lights are no elements: their light is gathered the same way, exactly.
    if (!tracer_.scene().lights.empty()) irradiance += pointLightIrradiance(tracer_, hit);
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
  const SourceTree sources_;
  std::vector<std::array<Vec3, 4>> polygons_;
  LinksByReceiver links_;  ///< link mode: the selected links by receiver tree node
};

std::unique_ptr<Renderer> createReichert(const RayTracer &tracer, const RenderContext &context,
                                         const Parameters &parameters) {
  SelectiveOptions selective = SelectiveOptions::from(parameters);
  selective.linkPower = parameters.real("selective-power");
  return std::make_unique<Reichert>(tracer, context, selective, parameters.choice("ff") == "point",
                                    parameters.real("cut-error"), int(parameters.integer("max-cut")));
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
      {"cut-error", ParameterType::Real, "0.02",
       "the gather's cut of the elements' tree is split while a node could give more than this fraction of the "
       "point's irradiance (Walter et al.'s lightcuts bound); 0: every element, the exact sum (slow on large meshes)",
       0, 1},
      {"max-cut", ParameterType::Integer, "256",
       "at most this many nodes in a point's cut (each one form factor and one shadow ray)", 1, 1 << 20}};
  for (const ParameterSpec &spec : selectiveParameters()) parameters.push_back(spec);
  parameters.push_back(selectivePowerParameter());
  return {"reichert", "form factors per pixel to every element (through a cut of their tree), ray-traced visibility",
          parameters, &createReichert,
          nullptr,    true};
}

}  // namespace radiant
