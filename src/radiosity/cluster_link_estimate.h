// The coupling of a hierarchical link with a cluster at one end or both
// (radiosity/cluster_tree.h), for the reflected light of `hierarchical-exact`.
//
// Seen from far enough away, a cluster is a point that sends its radiant
// intensity I(ω) = Σ_i (R_i A_i/π) max(0, n_i·ω) (its surfaces' own
// orientations: Sillion 1995's oriented clusters, RenderPark's "oriented"
// strategy) and receives irradiance that each of its surfaces takes with its
// own cosine. The link keeps the direction the light travels and a kernel
// that turns the source's intensity that way into irradiance; the solve
// multiplies them each sweep. The kernel is not the point model's
// cos θ/d² from the source's centre, which is biased dark (1/d² is convex,
// and the surfaces that face a receiver are nearer to it than the
// cluster's centre): it comes from exact point-to-patch form factors,
// Σ_j F(x → patch j), over the cluster's patches (an evenly spaced sample of
// 32 for a large one, each standing for its share of the area), divided by
// the projected area the intensity covers; into a cluster, it is scaled so
// that its surfaces take on average what they would from those factors.
// From a polygon into a cluster the direction is −Γ̂, Γ the polygon's vector
// form factor at the cluster's centre, which makes n_i·Γ exact in the
// source's shape and the surfaces' orientations.
//
// Visibility is sampled with a few deterministic rays between pairs of
// points (a node's interior points, patch centroids) chosen in proportion to
// the light each pair carries, so it weighs what the kernel weighs; a
// cluster's own surfaces may shadow each other (a knot's loops).
//
// What the refinement oracle needs besides: how far the kernel may be off
// (ClusterLinkEstimate::spread) and how many rays decided the visibility.
#pragma once

#include <span>

#include "mesh/mesh.h"
#include "radiosity/cluster_tree.h"
#include "radiosity/receiver_polynomial.h"
#include "radiosity/spherical_harmonics.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// One end of a link: a patch tree node or a cluster.
struct HierarchyEnd {
  const MeshTreeNode *node = nullptr;  ///< a tree node, or
  const Cluster *cluster = nullptr;    ///< a cluster
  Vec3 normal;                         ///< a tree node's front normal
  Box3 bounds;
  Vec3 centre;
  /// A cluster's patches (indices into mesh->patches), for the sums patch
  /// by patch where it is small or close.
  std::span<const uint32_t> patches;
  const RadiosityMesh *mesh = nullptr;
  /// A large cluster's projected area toward each direction as spherical
  /// harmonics (what the solve takes its intensity from); none for a small
  /// one, whose projected area is summed over its patches.
  const HarmonicBands *areaHarmonics = nullptr;
  /// Its projected area toward unit w, m², as the solve reckons it.
  double projectedArea(const Vec3 &w) const;

  static HierarchyEnd of(const MeshTreeNode &n, const Vec3 &normal);
  static HierarchyEnd of(const Cluster &c);
  bool isCluster() const { return cluster != nullptr; }
};

struct ClusterLinkEstimate {
  /// What turns the source's radiant intensity toward the receiver
  /// (direction), W·sr⁻¹, into irradiance, W·m⁻², visibility included: over
  /// a tree-node receiver a polynomial through its cubature points (from
  /// exact point-to-patch form factors), at a cluster receiver c[0] for a
  /// surface facing the source (its surfaces take it times their cosine).
  /// Isotropic (near field): what turns the source's mean R into irradiance.
  ReceiverPolynomial<double> kernel;
  Vec3 direction;         ///< unit, from the source's centre to the receiver's
  double kernelMean = 0;  ///< the kernel's mean over the receiver, m⁻²
  /// How far the kernel may be off, relative to its mean: over a tree node,
  /// what its polynomial misses at the cubature points; at a cluster
  /// receiver, whose surfaces all take the centre's distance, the point
  /// kernel at its box's corners against the centre's (first order). Huge
  /// when the centres do not see each other but some corners do.
  double spread = 0;
  double visibility = 1;  ///< fraction of the visibility rays unblocked
  int rays = 0;
  /// The near field: the kernel is per unit of the source's mean R, and a
  /// cluster receiver's surfaces all take the same (no direction holds).
  bool isotropic = false;
};

/// `overlap`: the ends' boxes meet, so neither is a point seen from the
/// other; such a pair must be split, not estimated.
bool endsOverlap(const HierarchyEnd &a, const HierarchyEnd &b);

/// `nearField`: the ends are too close for their centres to stand for them
/// (their boxes meet) and neither may be split further: the kernel is then
/// averaged over pairs of points on the two ends' surfaces instead of taken
/// from the source's centre.
ClusterLinkEstimate estimateClusterLink(const RayTracer &tracer, const HierarchyEnd &receiver,
                                        const HierarchyEnd &source, bool nearField = false);

}  // namespace radiant
