// Kok & Jansen's source selection (EG Rendering Workshop 1991; C&W §9.3.1):
// after the radiosity pass, the patches that reflect the most power become
// "secondary light sources" and are sampled per pixel with shadow rays, like
// the emitters. Their share of the interpolated indirect light is computed
// here, element by element, so that the renderer can remove it and nothing
// is counted twice.
#pragma once

#include <vector>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"
#include "render/renderer.h"
#include "util/parameters.h"

namespace radiant {

/// Which patches become secondary sources (kok's and multipass's parameters).
struct SecondarySourceOptions {
  int count = 0;        ///< the `count` patches reflecting the most power…
  double fraction = 0;  ///< …or, when > 0, the fewest carrying this fraction of the reflected power
  /// The visibility of each removed form factor, from grid × grid points on
  /// the source element (multipass's pass 2 takes 1: its image is a preview).
  int visibilityGrid = 1;
  InputLocation origin = InputLocation::ofParameter("sources");  ///< for errors about the selection

  /// From the parameters of secondarySourceParameters().
  static SecondarySourceOptions from(const Parameters &parameters);
};
/// sources, source-fraction, source-visibility-grid.
const ParameterTable &secondarySourceParameters();

struct SecondarySourceSample {
  Vec3 position;
  Vec3 normal;     ///< the patch's front side
  Bands radiance;  ///< reflected radiance (B − E)/π of the element at `position`
  double pdfArea = 0;
};

class SecondarySources {
 public:
  /// Selects patches by reflected power Σ (B − E)·A: the `options.count`
  /// largest, or the fewest carrying `options.fraction` of the total.
  /// Then computes removedRadiosity() for every element (parallel, deterministic).
  /// Where the solution refined a selected patch as a tree (hierarchical
  /// solvers: 10⁴ leaves behind a shadow), each receiver gathers from the
  /// tree's nodes that it sees under a small angle — node radius below
  /// openingRatio × distance — and from the leaves only near it, so the
  /// cost grows with the receivers times the log of the leaves; 0 gathers
  /// every leaf.
  static constexpr double kOpeningRatio = 0.25;
  SecondarySources(const RayTracer &tracer, const Solution &solution, const SecondarySourceOptions &options,
                   double openingRatio = kOpeningRatio);

  bool empty() const { return patches_.empty(); }
  const std::vector<uint32_t> &patches() const { return patches_; }
  /// Fraction of all reflected power the selected patches carry.
  double powerFraction() const { return powerFraction_; }
  /// A point uniformly on a selected patch, the patch chosen in proportion to its power.
  bool sample(double uSelect, double u1, double u2, SecondarySourceSample &out) const;
  /// Area density of sample() choosing a point on `patch` (0 if not selected).
  double pdfArea(uint32_t patch) const { return patch < pdfAreaOfPatch_.size() ? pdfAreaOfPatch_[patch] : 0.0; }
  /// The radiance sample() reports for a point of `element`.
  Bands radiance(uint32_t element) const;
  /// Per element i: ρ_i Σ_{k in selected patches} F(centre_i → k') V(k') (B_k − E_k), W·m⁻²,
  /// k' the part of element k in front of centre_i's tangent plane, V its visible fraction:
  /// what the solution's indirect radiosity holds from the selected sources.
  const std::vector<Bands> &removedRadiosity() const { return removed_; }
  /// The selected patches' elements, and how many pieces (elements or tree
  /// nodes) each receiver gathered from on average.
  size_t sourceElementCount() const { return sourceElements_; }
  double piecesPerReceiver() const { return piecesPerReceiver_; }

 private:
  void computeRemovedRadiosity(const RayTracer &tracer, int grid, double openingRatio, const InputLocation &origin);

  const Solution &solution_;
  std::vector<uint32_t> patches_;
  std::vector<double> cumulative_, probability_;
  std::vector<double> pdfAreaOfPatch_;  ///< by patch index
  double powerFraction_ = 0;
  std::vector<Bands> removed_;
  size_t sourceElements_ = 0;
  double piecesPerReceiver_ = 0;
};

}  // namespace radiant
