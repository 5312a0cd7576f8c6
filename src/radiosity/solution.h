// A view-independent radiosity solution: what every radiosity renderer reads.
//
// Units: radiosity B, exitance E and irradiance H in W·m⁻² per band
// ("radiosity units"); a Lambertian surface of radiosity B has radiance B/π.
// Per element, B = E + direct + indirect, where `direct` is what arrived
// straight from emitters (ρ Σ F E) and `indirect` the rest — the split that
// Shirley's two-pass method needs (C&W §9.3). Renderers read it at a point
// of the scene through radiosity/solution_query.h, which holds the front-side,
// texture (eq. 9.11) and clamping rules once.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "util/spectrum.h"

namespace radiant {

struct SolveStats {
  std::string solver;
  int iterations = 0;   ///< sweeps (Gauss–Seidel) or shots (progressive)
  double residual = 0;  ///< last sweep's max change of B over the largest B − E, or the unshot power fraction
  double seconds = 0;
  Bands emittedPower;   ///< Σ A E, W
  Bands absorbedPower;  ///< Σ A (1−ρ) H, W
  /// Measured by rays (radiosity/power_balance.h): what left the surfaces
  /// and lights and reached no surface's front (the open, a one-sided face's back), W.
  Bands escapedPower;
  /// Not kept in the solution file: the rest of the balance (power_balance.h).
  Bands unshotPower;                 ///< received, not yet sent on (progressive, stochastic), W
  Bands escapedToBackSides;          ///< of escapedPower, onto one-sided faces' backs or hidden parts, W
  double escapedStandardError = 0;   ///< of escapedPower's band average, W
  double powerBalanceTolerance = 0;  ///< |emitted − absorbed − escaped − unshot| this solver may reach, W
  double powerImbalance() const { return (emittedPower - absorbedPower - escapedPower - unshotPower).average(); }
  size_t formFactorRays = 0;
  /// Hierarchical solvers: the links at the end, and how many of them have a
  /// cluster at one end (not kept in the solution file).
  size_t links = 0, clusterLinks = 0;
  /// Carried on from a checkpoint after this many iterations (solve_checkpoint.h); −1: from the start.
  int resumedFromIteration = -1;
};

/// How much of a hierarchical link's source its receiver sees (from shadow rays).
enum class LinkVisibility : uint8_t { None = 0, Partial = 1, Full = 2 };

/// A hierarchical-radiosity link: `receiver` gathers F·B from `source`
/// (indices into RadiosityMesh::tree, at any level).
struct Link {
  uint32_t receiver = 0, source = 0;
  float formFactor = 0;       ///< F(receiver ← source), visibility included
  float visibleFraction = 0;  ///< of the shadow rays between them
  LinkVisibility visibility = LinkVisibility::Full;
  float carriedPower = 0;  ///< ρ_r F B_s A_r, W (band average): what the link transports
};

struct Solution {
  RadiosityMesh mesh;
  std::vector<Bands> reflectance;  ///< ρ per element (the diffuse part of its material)
  std::vector<Bands> emission;     ///< E = π·L_e per element, W·m⁻²
  std::vector<Bands> radiosity;    ///< B per element, W·m⁻²
  std::vector<Bands> direct;       ///< received straight from emitters, W·m⁻²
  std::vector<Bands> indirect;     ///< received after one or more reflections, W·m⁻²
  std::vector<Bands> unshot;       ///< progressive refinement's unshot radiosity, W·m⁻²
  std::vector<Bands> irradiance;   ///< H, arriving at the front, W·m⁻² (B = E + ρH + τH')
  /// τ per element, the diffuse transmittance of its material (radiosity/transmission.h):
  /// B gains τH', H' the irradiance on the other side of a translucent face.
  std::vector<Bands> transmittance;
  /// τH' per element, its direct share (τ times the other side's irradiance
  /// straight from the emitters) and the rest. Part of `radiosity`, `direct`
  /// and `indirect`; kept apart for the display at nodes (hasNodeIrradiance),
  /// which forms ρ̄H from the node irradiances. Empty when nothing is translucent.
  std::vector<Bands> transmittedDirect, transmittedIndirect;
  Bands ambient;  ///< progressive refinement's ambient term (display only)
  /// The part of `ambient` that is not the first arrival of still-unshot
  /// emission: what a method that samples the emitters per pixel (shirley,
  /// kok) may add as indirect light without counting direct light twice.
  Bands indirectAmbient;
  std::vector<double> errorEstimate;  ///< per element: max relative difference between its nodes and itself
  std::vector<Bands>
      nodeRadiosity;  ///< display B (ambient included) at mesh nodes: area-weighted average of the elements around
  /// When the solver computed them at the nodes themselves (hierarchical-exact):
  /// the irradiance arriving there straight from the emitters, exact
  /// (radiosity/backprojection.h), and after reflections, W·m⁻². nodeRadiosity
  /// is then E + ρ̄(direct + indirect) at each node instead of an average of
  /// the elements around it. Both empty otherwise.
  std::vector<Bands> nodeDirectIrradiance, nodeIndirectIrradiance;
  /// The direct irradiance the meshing already computed exactly, at nodes
  /// and as elements' means (radiosity/direct_light_mesh.h), NaN where it
  /// did not: the stochastic solver evaluates only the rest. Empty
  /// otherwise; not kept in the solution file.
  std::vector<Bands> knownNodeDirect, knownElementDirect;
  bool hasNodeIrradiance() const {
    return !mesh.nodes.empty() && nodeDirectIrradiance.size() == mesh.nodes.size() &&
           nodeIndirectIrradiance.size() == mesh.nodes.size();
  }
  /// The indirect radiosity at the nodes (reflected light that arrived after
  /// at least one reflection, plus indirectAmbient's share), what shirley and
  /// kok interpolate: from nodeIndirectIrradiance when there is one, else the
  /// node values of the elements' indirect radiosity.
  std::vector<Bands> nodeIndirectRadiosity() const;
  /// The direct radiosity at the nodes (reflected light that arrived straight
  /// from the emitters), formed as nodeIndirectRadiosity is: from
  /// nodeDirectIrradiance when there is one, else the node values of `direct`.
  std::vector<Bands> nodeDirectRadiosity() const;
  /// ρ̄ at the nodes (nodeValues of `reflectance`): with textures, the texture
  /// averaged over each element; recomputed by updateNodesAndErrors and on reading.
  std::vector<Bands> nodeReflectance;
  std::vector<Link> links;           ///< hierarchical solver only
  std::vector<Bands> treeRadiosity;  ///< B of every mesh.tree node (hierarchical solver only)
  SolveStats stats;

  size_t elementCount() const { return mesh.elements.size(); }
  /// τ of an element (0 when the solution has no transmittances).
  Bands transmittanceOf(size_t e) const { return e < transmittance.size() ? transmittance[e] : Bands(0.0); }
  /// What an element absorbs of its irradiance, 1 − ρ − τ.
  Bands absorptance(size_t e) const { return Bands(1.0) - reflectance[e] - transmittanceOf(e); }
  bool hasTransmitted() const {
    return transmittedDirect.size() == elementCount() && transmittedIndirect.size() == elementCount();
  }
  /// Radiosity for display: B plus, when `withAmbient`, (ρ + τ)·ambient.
  Bands displayRadiosity(uint32_t element, bool withAmbient = true) const {
    if (!withAmbient) return radiosity[element];
    return radiosity[element] + (reflectance[element] + transmittanceOf(element)) * ambient;
  }
  /// B interpolated from the nodes at a location (continuous within a patch).
  Bands interpolatedRadiosity(const MeshLocation &location) const { return interpolate(nodeRadiosity, location); }
  /// Node values of any per-element quantity, formed exactly as nodeRadiosity
  /// is (area-weighted average of the elements around a node, pooled across
  /// the patches of one smooth surface, T-vertices on their edges), so two
  /// such fields interpolate consistently and may be subtracted.
  std::vector<Bands> nodeValues(const std::vector<Bands> &perElement) const;
  /// The same with the pools given (nodePools()), for several fields at once.
  std::vector<Bands> nodeValues(const std::vector<Bands> &perElement, const std::vector<uint32_t> &pools) const;
  /// A field of node values (nodeRadiosity or from nodeValues) interpolated at a location.
  Bands interpolate(const std::vector<Bands> &values, const MeshLocation &location) const;
  /// Recomputes nodeRadiosity, nodeReflectance and errorEstimate from the element radiosities (including ambient).
  void updateNodesAndErrors();
  /// Gives every node of a pool of facets (nodePools; some patch's normal
  /// more than 2° from the first's, joined by their shading normals) the
  /// same node irradiances, the area-weighted mean of its nodes' (weighted
  /// as nodeValues weighs them), for a solver that computed them per patch
  /// (hierarchical-exact), so the display has no seam where the facets
  /// meet. Every other node keeps its own bit for bit.
  void poolNodeIrradiance();
  /// For every node, the first node of its pool: the nodes at one place on
  /// neighbouring patches of one smooth surface (same material, normals or
  /// shading normals within 2°: RadiosityMesh::sameSmoothSurface; none on a
  /// cut), which share their values so that the
  /// interpolation has no seam there. A node alone is its own. Kept for the
  /// mesh it was found on (a sort of the nodes: 0.3 s at 2·10⁶, asked for by
  /// the solver's every node field) and found again when the mesh changes.
  std::vector<uint32_t> nodePools() const;

 private:
  /// nodePools()'s answer and the fingerprint of the mesh it is for; copies
  /// of a solution share it (the fingerprint tells whether it is theirs).
  struct NodePoolMemo {
    std::mutex mutex;
    uint64_t meshFingerprint = 0;
    std::vector<uint32_t> pools;
  };
  std::shared_ptr<NodePoolMemo> nodePoolMemo_ = std::make_shared<NodePoolMemo>();
  std::vector<uint32_t> findNodePools() const;
  /// Pools the area-weighted sums of coincident nodes of neighbouring patches of one smooth surface.
  void shareNodesAcrossPatches(std::vector<Bands> &sums, std::vector<double> &weight,
                               const std::vector<uint32_t> &pool) const;
  /// Sets every T-vertex to the mean of its edge's ends, coarse to fine, so interpolation does not crack.
  void applyTVertices(std::vector<Bands> &values) const;

 public:
};

/// An empty solution on `mesh` with ρ and E from the scene's materials.
Solution initialSolution(const Scene &scene, RadiosityMesh mesh);

}  // namespace radiant
