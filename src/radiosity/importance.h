// Importance for the hierarchical solver's `--importance`: view-dependent
// refinement after Smits, Arvo & Salesin, "An importance-driven radiosity
// algorithm", SIGGRAPH 1992 (abstract verified; equations derived here, see
// docs/radiosity.md#importance-driven-refinement---importance).
//
// Radiosity answers "how bright is every surface"; a view asks only for the
// surfaces it shows and for the light that reaches them. Smits et al. solve a
// second, dual transport problem beside the radiosity one: *importance* is
// emitted by the eye and travels over the same links the other way, so a
// surface is important when it is seen, or lights what is seen, or lights
// what lights it. Links are then refined by radiosity × importance, and
// what neither shows nor lights the view stays coarse.
//
// The measurement. Let R_ℓ be the fraction of the pixels of a small image of
// the view (ImportanceView::resolution rows, one ray through each pixel
// centre) whose ray first hits the front of leaf ℓ. Then M = Σ_ℓ R_ℓ B_ℓ is
// π times the mean pixel radiance of the view (pixels that miss count 0).
//
// The adjoint. With push–pull, the hierarchical system on the leaves is
// B = E + K B with K_ℓm = ρ_ℓ Σ F(a ← s) A_m / A_s over the links (a ← s)
// whose receiver a contains ℓ and whose source s contains m (F(a ← s) as in
// radiosity/solution.h's Link: what a gathers from s). So
//   M = Rᵀ (I − K)⁻¹ E = Yᵀ E   with   Y = R + Kᵀ Y,
// the importance equation: Y_m = R_m + Σ_links (A_m / A_s) F(a ← s) Σ_{ℓ ⊂ a} ρ_ℓ Y_ℓ.
// In densities Ŷ = Y / A (m⁻²; Bekaert's "potential" in RenderPark):
//   Ŷ_m = R_m / A_m + Σ_{links a ← s, s ⊇ m} F(a ← s) (A_a / A_s) ⟨ρ Ŷ⟩_a,
// ⟨·⟩_a the area average over a. By reciprocity F(a ← s) A_a / A_s = F(s ← a):
// importance is the radiosity solve with every link reversed. Each source
// gathers G_s from the receivers of its links, G is pushed down to the
// leaves, a leaf takes Ŷ = R/A + ΣG, and Ŷ and ρŶ are pulled up as area
// averages. At convergence Σ_m Y_m E_m = Σ_ℓ R_ℓ B_ℓ per band (both sides are
// the measurement), which the tests check.
//
// The refinement weight. A link (p ← q) is accurate enough when
//   F(p ← q) · max over bands of (B_q Ŷmax_p) / Ŷ_ref ≤ ε,
// the BF criterion with B_q weighted by the receiver's importance, against the
// same ε = --link-threshold × max E. Ŷmax_p is the largest importance density
// anywhere in p, not its mean: a floor of which the view shows one corner must
// be refined for that corner, and its mean would dilute it by the part out of
// view. Its visual part is the largest pointwise density among p's pixels, a
// pixel's density being 1 / (pixels × its footprint on the surface); its
// propagated part is the largest Ŷ − R/A among p's leaves. Ŷ_ref = (Σ R) /
// (visible area), the visible area being the sum of the footprints of the
// pixels that hit: the visual importance density of what the view shows, taken
// as a whole. So a surface in view weighs about 1 and is refined about as
// plain BF would refine it (more when near, where its pixels are smaller, less
// when far); one out of view weighs what it passes on to the view, usually
// far less. Nodes made while refining start from their own pixels plus what
// their parent had received through links.
#pragma once

#include <array>
#include <vector>

#include "radiosity/solution.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// A node's polygon as the hierarchy subdivides it.
struct ImportanceNodeShape {
  int vertexCount = 4;
  std::array<Vec3, 4> corners{};
  double area = 0;  ///< m²
};

/// Visual importance R per node: the fraction of the view's pixels whose
/// centre ray first hits the node's front. Nodes 0 … patches−1 are the
/// patches (the trees' roots); split() hands a node's pixels to its children.
class VisualImportance {
 public:
  VisualImportance(const RayTracer &tracer, const RadiosityMesh &mesh, const ImportanceView &view);
  /// `children` become nodes (of the parent's patch); each of the parent's
  /// pixel hits goes to the first child whose polygon contains it.
  void split(uint32_t parent, const std::array<uint32_t, 4> &children, const std::array<ImportanceNodeShape, 4> &shapes,
             const Vec3 &normal);
  double fraction(uint32_t node) const {
    return node < pixelCount_.size() ? double(pixelCount_[node]) / double(pixels_) : 0.0;
  }
  /// The largest pointwise visual importance density among the node's pixels, m⁻² (0 without any).
  double largestDensity(uint32_t node) const { return node < largest_.size() ? largest_[node] : 0.0; }
  /// Σ R: the fraction of pixels that hit the front of some surface.
  double totalFraction() const { return double(hits_) / double(pixels_); }
  /// The area those pixels cover (Σ of their footprints), m²: the visible area.
  double visibleArea() const { return visibleArea_; }
  size_t pixels() const { return pixels_; }

 private:
  struct PixelHit {
    Vec3 position;
    double density;  ///< 1 / (pixels × footprint), m⁻²
  };
  void grow(uint32_t node);
  std::vector<std::vector<PixelHit>> hitsOf_;  ///< per node: its pixel hits, until it is split
  std::vector<uint32_t> pixelCount_;           ///< per node: pixel hits inside it (kept after a split)
  std::vector<double> largest_;                ///< per node: the largest density among them
  size_t pixels_ = 1, hits_ = 0;
  double visibleArea_ = 0;
};

/// The hierarchy as importance travels over it: the trees (nodes 0 … roots−1
/// are the roots) and the links.
struct ImportanceGraph {
  struct Link {
    uint32_t receiver = 0, source = 0;
    double formFactor = 0;  ///< F(receiver ← source)
  };
  uint32_t roots = 0;
  std::vector<std::array<int32_t, 4>> children;  ///< per node, −1 at a leaf
  std::vector<double> area;                      ///< per node, m²
  std::vector<Bands> reflectance;                ///< per node; read at the leaves
  std::vector<double> visual;                    ///< R per node; read at the leaves
  std::vector<Link> links;
};

/// Solves the importance equation on `graph` by Jacobi sweeps (gather over
/// the reversed links, push–pull), starting from `density` (Ŷ per node, m⁻²;
/// resized and started from R/A where it is short). Stops when a sweep changes
/// no leaf's Ŷ by more than `tolerance` × the largest propagated Ŷ − R/A of a
/// leaf, or after `maxSweeps`. With `largestReceived`, also gives per node the
/// largest Ŷ − R/A of its leaves. Returns the sweeps taken.
int propagateImportance(const ImportanceGraph &graph, std::vector<Bands> &density, double tolerance, int maxSweeps,
                        std::vector<Bands> *largestReceived = nullptr);

/// What the hierarchical solver keeps for --importance: per node its visual
/// importance and its importance density, and the refinement weight.
class ImportanceRefinement {
 public:
  /// Throws InputError when the view sees no surface's front.
  ImportanceRefinement(const RayTracer &tracer, const RadiosityMesh &mesh, const ImportanceView &view);
  /// A node was split: its children get their own pixels and its propagated importance.
  void split(uint32_t parent, const std::array<uint32_t, 4> &children, const std::array<ImportanceNodeShape, 4> &shapes,
             const Vec3 &normal);
  /// The source's radiosity as the oracle weighs it for this receiver:
  /// max over bands of B_source · Ŷmax_receiver / Ŷ_ref.
  double weightedRadiosity(uint32_t receiver, const Bands &sourceRadiosity) const;
  /// Propagates importance over the current links (`graph`, whose `visual`
  /// is filled here); returns the sweeps taken.
  int propagate(ImportanceGraph graph, double tolerance, int maxSweeps);
  const std::vector<Bands> &density() const { return density_; }

 private:
  VisualImportance visual_;
  std::vector<Bands> density_;   ///< Ŷ per node (area mean), m⁻²
  std::vector<Bands> received_;  ///< per node: the largest Ŷ − R/A of its leaves, m⁻²
  std::vector<double> area_;     ///< per node, m²
  double reference_ = 1;         ///< Ŷ_ref, m⁻²
};

/// Importance of a solved hierarchical solution (its trees and links) for a
/// view, per tree node: R (fraction of pixels) and Ŷ (m⁻²). For tests and
/// benchmarks: the solver's own propagation on what it saved.
struct SolutionImportance {
  std::vector<double> visual;
  std::vector<Bands> density;
};
SolutionImportance solutionImportance(const RayTracer &tracer, const Solution &solution, const ImportanceView &view,
                                      double tolerance = 1e-9, int maxSweeps = 10000);

}  // namespace radiant
