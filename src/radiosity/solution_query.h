// Reading the radiosity solution at a point of the scene: the one way every
// renderer asks what light the solution puts there — the displays (`flat`,
// `interpolate`), the path tracer's multipass reads, the two-pass methods,
// Chen's bump gather and Kok's secondary sources.
//
// Three rules hold for every reading, so the methods cannot drift apart:
//
// - Front side. The solution is one-sided: an element's B leaves its front
//   (the face's counter-clockwise side). A hit seen from behind, or on a face
//   the mesh left out (mirrors, glass), holds nothing: locateHit says no.
// - Texture (C&W eq. 9.11). The solution reflected with the mean reflectance
//   ρ̄; at a point of texture value ρ(x) the reflected part is scaled:
//   B(x) = E + (B̂(x) − E)·ρ(x)/ρ̄(x). Emission is never scaled. ρ̄ is the
//   one the reconstruction uses: interpolated from the nodes like B̂
//   (continuous, no seams at element edges), or the element's own for the
//   constant display (so an element's mean stays its B).
// - Clamping. What a surface reflects is never negative: B − E is clamped at
//   0 per band after the scale. Interpolation (T-vertices, the nodes of a
//   patch pooled with a neighbour's) and subtractions (kok's removal) can
//   undershoot by round-off or more; a negative reflection would darken its
//   neighbours' pixels below what the solution says.
//
// Plain data plus free functions: a SolutionPoint is found once per hit and
// read as often as a method needs.
#pragma once

#include <functional>
#include <vector>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// C&W §9.2's two displays of a constant-element solution: each element's
/// own B (the mesh made visible), or B̂ interpolated from the nodes
/// (bilinear on quads, barycentric on triangles: Gouraud shading).
enum class Reconstruction { Constant, Interpolated };

/// A point of the scene where the solution is read.
struct SolutionPoint {
  MeshLocation location;  ///< the element and the point's coordinates in it
  Reconstruction reconstruction = Reconstruction::Interpolated;
  /// What scales the reflected radiosity B − E read here: eq. 9.11's
  /// ρ(x)/ρ̄ where the material has a diffuse texture (applySurfaceDetail),
  /// times whatever else a renderer scales reflected light by (Chen's bump
  /// ratio, render/bump_gather.h). Exactly 1 otherwise.
  Bands reflectedScale{1.0};
  /// The material has surface detail (texture, bump or normal map): readings
  /// go through E + (B − E)·reflectedScale. Without, B is read as it is.
  bool scaled = false;
};

/// Locates a hit seen from direction `wo` (towards the viewer) on the
/// solution's mesh, by the front-side rule above: false on the back of a
/// face (dot(wo, geometric normal) ≤ 0) or a face with no patch.
bool locateHit(const Solution &solution, const Hit &hit, const Vec3 &wo, SolutionPoint &out,
               Reconstruction reconstruction = Reconstruction::Interpolated);

/// C&W eq. 9.11's factor ρ(x)/ρ̄ at a location, ρ̄ as `reconstruction` takes
/// it (interpolated from nodeReflectance, or the element's). Where ρ̄ = 0
/// nothing was reflected and the factor is 0.
Bands textureFactor(const Solution &solution, const MeshLocation &location, const Bands &rho,
                    Reconstruction reconstruction = Reconstruction::Interpolated);

/// Sets the point's scale for its material: `scaled` when it has surface
/// detail, and reflectedScale = textureFactor(ρ(x)) when it has a diffuse
/// texture (`rho`: ρ(x), the diffuse reflectance with the texture applied).
void applySurfaceDetail(const Solution &solution, const Material &material, const Bands &rho, SolutionPoint &point);

/// The reflected radiosity B − E at the point, W·m⁻², scaled and clamped at 0.
Bands reflectedRadiosity(const Solution &solution, const SolutionPoint &point);
/// The same as radiance (a Lambertian surface of radiosity B has radiance B/π).
inline Bands reflectedRadiance(const Solution &solution, const SolutionPoint &point) {
  return reflectedRadiosity(solution, point) * kInvPi;
}
/// The radiosity at the point, emission included: E + reflectedRadiosity.
/// Unscaled, that is max(B, E) per band, computed without the round trip
/// through B − E so that B reads back exactly.
Bands radiosity(const Solution &solution, const SolutionPoint &point);
/// An element's own reflected radiosity (the constant reconstruction, no
/// texture): what it sends to others, for methods that treat elements as
/// sources (kok). Ambient included, as in the display.
Bands reflectedRadiosity(const Solution &solution, uint32_t element);

/// The split of reflected radiosity that Shirley's method needs (C&W §9.3):
/// what arrived straight from the emitters, and what after one or more
/// reflections (indirectAmbient included). Node values, read like B̂.
enum class Field { Direct, Indirect };
std::vector<Bands> nodeField(const Solution &solution, Field field);
/// A field of reflected radiosity (node values from nodeField, or derived
/// from one) read at a point as radiance: field(x)/π·reflectedScale, clamped
/// at 0 like every reading. The point's reconstruction must be Interpolated.
Bands fieldRadiance(const Solution &solution, const std::vector<Bands> &nodeValues, const SolutionPoint &point);

/// The gradient error estimate of the point's element (Solution::errorEstimate,
/// relative): what --selective compares with its threshold.
double errorEstimate(const Solution &solution, const SolutionPoint &point);

/// A hierarchical solution keeps its links and the B of every tree node;
/// only then can a method re-evaluate the links that light a point.
bool isHierarchical(const Solution &solution);

/// The links that deliver light to each leaf of a hierarchical solution:
/// a leaf receives through its own links and, by push–pull (Hanrahan,
/// Salzman & Aupperle 1991), through every ancestor's.
struct LinksByReceiver {
  std::vector<int32_t> parent;               ///< per mesh.tree node, −1 at a root
  std::vector<int32_t> leafOfElement;        ///< per element, its tree leaf or −1 (grid patches)
  std::vector<std::vector<uint32_t>> links;  ///< per tree node: indices into Solution::links it receives
};
/// Indexes the links for which `keep` holds (all of them without one).
LinksByReceiver indexLinksByReceiver(const Solution &solution, const std::function<bool(const Link &)> &keep = {});
/// Calls visit(link) for every indexed link that lights `element`: its
/// leaf's first, then each ancestor's, in index order.
template <typename Visit>
void forEachLinkLighting(const Solution &solution, const LinksByReceiver &index, uint32_t element, Visit &&visit) {
  for (int32_t t = index.leafOfElement[element]; t >= 0; t = index.parent[size_t(t)])
    for (uint32_t l : index.links[size_t(t)]) visit(solution.links[l]);
}

}  // namespace radiant
