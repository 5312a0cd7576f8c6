#include "render/secondary_sources.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <fmt/format.h>
#include <numeric>

#include "radiosity/form_factor.h"
#include "render/sampling.h"
#include "util/error.h"

namespace radiant {

namespace {

/// (B − E) of an element, ambient included as in the display: what it reflects.
Bands reflectedRadiosity(const Solution &s, uint32_t element) {
  Bands b = s.displayRadiosity(element) - s.emission[element];
  for (int k = 0; k < kBandCount; ++k) b[k] = std::max(0.0, b[k]);
  return b;
}

/// Above this many receiver × source-element pairs the removal would take
/// minutes; the user should select fewer sources.
constexpr double kMaxPairs = 2e8;

}  // namespace

SecondarySources::SecondarySources(const RayTracer &tracer, const Solution &solution, const RendererOptions &options)
    : solution_(solution) {
  const RadiosityMesh &mesh = solution.mesh;
  std::vector<double> power(mesh.patches.size(), 0.0);
  double total = 0;
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    double p = reflectedRadiosity(solution, e).average() * mesh.elements[e].area;
    power[mesh.elements[e].patch] += p;
    total += p;
  }
  std::vector<uint32_t> order(mesh.patches.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return power[a] > power[b]; });
  double selected = 0;
  for (uint32_t p : order) {
    if (power[p] <= 0) break;
    if (options.secondarySourceFraction > 0 ? selected >= options.secondarySourceFraction * total
                                            : patches_.size() >= size_t(std::max(0, options.secondarySources)))
      break;
    patches_.push_back(p);
    selected += power[p];
  }
  powerFraction_ = total > 0 ? selected / total : 0;
  double running = 0;
  for (uint32_t p : patches_) {
    probability_.push_back(power[p] / selected);
    running += probability_.back();
    cumulative_.push_back(running);
  }
  if (!cumulative_.empty()) cumulative_.back() = 1.0;
  pdfAreaOfPatch_.assign(mesh.patches.size(), 0.0);
  for (size_t j = 0; j < patches_.size(); ++j) pdfAreaOfPatch_[patches_[j]] = probability_[j] / mesh.patches[patches_[j]].area;
  computeRemovedRadiosity(tracer, std::max(1, options.removalVisibilityGrid));
}

void SecondarySources::computeRemovedRadiosity(const RayTracer &tracer, int grid) {
  const RadiosityMesh &mesh = solution_.mesh;
  const Solution &s = solution_;
  // The selected patches' elements, with their polygons and values, once.
  struct Source {
    uint32_t element;
    std::vector<Vec3> polygon;
    Bands reflected;
  };
  std::vector<Source> sources;
  for (uint32_t p : patches_)
    for (uint32_t k = 0; k < mesh.patches[p].elementCount; ++k) {
      uint32_t e = mesh.patches[p].firstElement + k;
      sources.push_back({e, mesh.polygon(e), reflectedRadiosity(s, e)});
    }
  if (double(sources.size()) * double(mesh.elements.size()) > kMaxPairs)
    throw InputError(InputLocation{"--sources"},
                     fmt::format("{} source elements × {} receivers is too many form factors; select fewer sources",
                                 sources.size(), mesh.elements.size()));
  removed_.assign(mesh.elements.size(), Bands(0.0));
  tbb::parallel_for(size_t(0), mesh.elements.size(), [&](size_t i) {
    const Element &receiver = mesh.elements[i];
    const Vec3 &n = mesh.normalOf(uint32_t(i));
    std::vector<Vec3> front;
    Bands gathered(0.0);
    for (const Source &source : sources) {
      const Element &k = mesh.elements[source.element];
      if (k.patch == receiver.patch) continue;
      const Vec3 &nk = mesh.normalOf(source.element);
      if (dot(receiver.centre - k.centre, nk) <= 0) continue;  // behind the source: its front faces away
      // The part of the source in front of the receiver, its exact factor,
      // and its visible fraction from grid × grid stratified points on that part.
      clipToFrontHalfSpace(receiver.centre, n, source.polygon, front);
      if (front.size() < 3) continue;
      double f = formFactorPointToPolygon(receiver.centre, n, front);
      if (f <= 0) continue;
      int visible = 0;
      for (int a = 0; a < grid; ++a)
        for (int b = 0; b < grid; ++b)
          visible +=
              tracer.visible(receiver.centre, n, sampleConvexPolygon(front, (a + 0.5) / grid, (b + 0.5) / grid), nk);
      gathered += source.reflected * (f * visible / double(grid * grid));
    }
    removed_[i] = s.reflectance[i] * gathered;
  });
}

Bands SecondarySources::radiance(uint32_t element) const { return reflectedRadiosity(solution_, element) * kInvPi; }

bool SecondarySources::sample(double uSelect, double u1, double u2, SecondarySourceSample &out) const {
  if (patches_.empty()) return false;
  size_t j = std::upper_bound(cumulative_.begin(), cumulative_.end(), uSelect) - cumulative_.begin();
  j = std::min(j, patches_.size() - 1);
  const Patch &patch = solution_.mesh.patches[patches_[j]];
  out.position = samplePlanarPolygon(patch.corners.data(), patch.vertexCount, u1, u2);
  out.normal = patch.normal;
  MeshLocation location = solution_.mesh.locate(patch.face, out.position);
  out.radiance = radiance(location.element);
  out.pdfArea = probability_[j] / patch.area;
  return true;
}

}  // namespace radiant
