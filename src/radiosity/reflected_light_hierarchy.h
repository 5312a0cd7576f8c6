// The reflected light of `hierarchical-exact` (radiosity/hierarchical_exact.cpp):
// hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991) over links
// between the nodes of the patches' subdivision trees and, above the
// patches, clusters of them (radiosity/cluster_tree.h; Smits, Arvo &
// Greenberg 1994; Sillion 1995), gathering the sources' reflected radiosity
// R = B − E (the emission's first arrival is the exact direct light).
//
// - Links between two tree nodes (reflected_light_hierarchy.cpp): the form
//   factor exact at each of the receiver's cubature points, visibility
//   included (radiosity/link_estimate.h), kept as polynomials over the
//   receiver, one per term of the source's R, itself a polynomial
//   (radiosity/receiver_polynomial.h).
// - Links with a cluster at one end or both (reflected_light_clusters.cpp):
//   the cluster is a point that sends its radiant intensity I(ω) = Σ R_i A_i
//   max(0, n_i·ω)/π and whose surfaces each take the irradiance with their
//   own cosine (radiosity/cluster_link_estimate.h). Small clusters (at most
//   kExactClusterPatches patches) are summed patch by patch; larger ones
//   carry I(ω), and the radiance they gather, as spherical harmonics
//   (radiosity/spherical_harmonics.h).
//
// Refinement starts from one link, the root cluster with itself, and
// replaces a link by links from the children of the larger end while the
// oracle says the link's error exceeds the threshold. The oracle bounds the
// error a link makes rather than the light it carries (Bekaert & Willems
// 1996, "Error control for radiosity"; RenderPark's Galerkin radiosity):
// how far the point form factors stray from their polynomial times the
// source's R, plus the form factor times how far the source's children stray
// from its polynomial; for a cluster link, the kernel's variation over the
// two ends times the largest R in the source, the visibility rays'
// disagreement, and the spherical harmonics' error. Two ends whose boxes
// meet are always split.
//
// Refinement runs in batches: every pending pair's link in a batch is
// estimated in parallel, then the decisions are applied in order, so the
// solution does not depend on the thread count. Then gather (each node sums
// its links, in parallel) and push–pull (clusters to patches, then per
// patch in parallel, then patches to clusters) until R settles; then the
// links are re-examined with the solved R (multigridding) and the system
// solved again.
#pragma once

#include <tbb/task_arena.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/cluster_link_estimate.h"
#include "radiosity/cluster_tree.h"
#include "radiosity/direct_refinement.h"
#include "radiosity/link_estimate.h"
#include "radiosity/receiver_polynomial.h"
#include "radiosity/solution.h"
#include "radiosity/solver.h"
#include "radiosity/spherical_harmonics.h"
#include "raytrace/face_tree.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

class ReflectedLightHierarchy {
 public:
  ReflectedLightHierarchy(const Scene &scene, const RayTracer &tracer, RadiosityMesh &mesh, DirectLightField &field,
                          const SolverOptions &options, double minimumEdge);

  /// The direct light's mean over every node, from the field (evaluating what
  /// is missing), and R = ρ·H_direct as the first estimate of the sources.
  void initialiseFromDirectLight();
  /// The link error allowed, W·m⁻² of reflected radiosity.
  void setThreshold(double absolute) { threshold_ = absolute; }
  /// Links the root cluster with itself and refines.
  void link();
  /// Multigridding: re-examines every link with the current R; returns how many were refined.
  size_t rerefine();
  /// Gather + push–pull until R settles; returns the sweeps taken.
  int solve(double tolerance, int maxSweeps, double &residual, const SolverProgressCallback &progress, int &total,
            std::chrono::steady_clock::time_point start);

  void writeTo(Solution &s) const;
  size_t rays() const { return rays_; }
  size_t linkCount() const;
  size_t clusterLinkCount() const;

  /// Clusters of at most this many patches send and receive patch by patch;
  /// larger ones through spherical harmonics.
  static constexpr uint32_t kExactClusterPatches = 8;
  /// The irradiance of a black receiver matters too (what it absorbs, the
  /// illuminance it reports): the oracle weighs it as a dark grey one, not by 0.
  static constexpr double kLeastReflectance = 0.05;
  /// How far the spherical harmonics may be off, relative to what a link
  /// through a large cluster carries (spherical_harmonics.h: about 9 % of a
  /// single lobe's peak, less for a spread of orientations).
  static constexpr double kHarmonicsError = 0.1;

 private:
  // Node ids: a tree node's index, or a cluster's with kClusterBit set.
  static constexpr uint32_t kClusterBit = 0x80000000u;
  static bool isCluster(uint32_t id) { return (id & kClusterBit) != 0; }
  static uint32_t clusterIndex(uint32_t id) { return id & ~kClusterBit; }
  static uint32_t clusterId(uint32_t cluster) { return cluster | kClusterBit; }
  // Link indices in a tree node's list: into records_, or into clusterRecords_ with kClusterBit set.

  struct PendingPair {
    uint32_t receiver, source;
    bool clearShaft = false;  ///< known unoccluded from a parent pair (tree nodes only)
  };

  /// A link between two tree nodes (LinkEstimate): 40 bytes, 44 with its
  /// index in the receiver's list (the form factor is shape's mean over the receiver).
  struct LinkRecord {
    uint32_t receiver, source;
    ReceiverPolynomial<float> shape;
    std::array<float, 2> moments;
    float spread = 0;
    bool clearShaft = false;
    bool alive = true;
  };
  static_assert(sizeof(LinkRecord) == 40, "docs/PERFORMANCE.md quotes the bytes per link");

  /// A link with a cluster at one end or both (ClusterLinkEstimate).
  struct ClusterLinkRecord {
    uint32_t receiver, source;
    ReceiverPolynomial<float> kernel;  ///< visibility included
    std::array<float, 3> direction;
    float kernelMean = 0;  ///< unoccluded
    float spread = 0, visibility = 1;
    uint8_t rays = 0;
    bool alive = true;
    bool nearField = false;
    Vec3 directionVector() const { return {direction[0], direction[1], direction[2]}; }
  };

  // --- tree nodes (reflected_light_hierarchy.cpp)
  void addNodeData(uint32_t n);
  const Vec3 &normalOf(uint32_t n) const { return mesh_.patches[mesh_.tree[n].patch].normal; }
  double formFactorOf(const LinkRecord &l) const { return l.shape.mean(mesh_.tree[l.receiver].vertexCount == 4); }
  LinkEnd end(uint32_t n) const { return {mesh_.tree[n], normalOf(n), mesh_.patches[mesh_.tree[n].patch].face}; }
  ReceiverPolynomial<Bands> directShape(uint32_t n) const;
  void pullShapes(uint32_t n);
  void pullDirect(uint32_t n);
  bool facing(uint32_t a, uint32_t b) const;
  bool canSplit(uint32_t n) const;
  Bands computeVariation(uint32_t n) const;
  void updateVariation();
  double error(uint32_t r, uint32_t s, double formFactor, double spreadOfF) const;
  void splitNode(uint32_t n);
  void refine(std::vector<PendingPair> pending);
  /// The MPI rank that estimates the links into a receiver (a tree node or
  /// cluster id): id mod ranks, all of them with one rank.
  static bool ownsReceiver(uint32_t id);
  void initialiseNewLeaves();
  Bands pushPull(uint32_t n, const ReceiverPolynomial<Bands> &down, double &change, double &largest);
  /// One gather over every link, through the clusters to their patches.
  /// With several MPI ranks each gathers into the receivers it owns
  /// (ownsReceiver), and the gathered values are then shared, bit for bit.
  /// Called outside arena_ (it enters it), from the thread that calls MPI.
  void gatherAll();
  /// What gatherAll's receivers gathered, from their owners to every rank.
  void shareGathered();
  /// Each leaf's Σ_j F_ij from one gather of R = 1, and the scale that holds it to 1.
  void measureClosure();
  void gatherTreeNode(uint32_t n);

  // --- clusters (reflected_light_clusters.cpp)
  void initialiseClusters();
  HierarchyEnd hierarchyEnd(uint32_t id) const;
  /// Children to refine an end into: a node's four (split first), a cluster's own patches and child clusters.
  void childrenOf(uint32_t id, std::vector<uint32_t> &out);
  double sizeOf(uint32_t id) const;
  /// A cluster splits down to the smallest link size, as a node does:
  /// below it, however many patches it holds, it is one end of a link (the
  /// light between surfaces closer than that is carried at that size), so
  /// the links do not grow with the tessellation.
  bool canSplitEnd(uint32_t id) const;
  bool facingEnds(uint32_t a, uint32_t b) const;
  /// Replaces the pair by pairs with the children of its larger splittable
  /// end (both ends' children for a cluster with itself); false when neither can split.
  bool splitPair(uint32_t r, uint32_t s, bool clearShaft, std::vector<PendingPair> &pending);
  /// R's radiant intensity from `source` toward unit `w` over π·R: the projected area (m²) when `area`.
  Bands intensity(uint32_t source, const Vec3 &w) const;
  double projectedArea(uint32_t source, const Vec3 &w) const;
  Bands largestReflected(uint32_t id) const;
  Bands meanReflected(uint32_t id) const;
  double clusterLinkError(uint32_t r, uint32_t s, const ClusterLinkEstimate &e) const;
  double clusterLinkError(const ClusterLinkRecord &l) const;
  void keepClusterLink(uint32_t r, uint32_t s, const ClusterLinkEstimate &e, bool nearField);
  void gatherCluster(uint32_t c);
  /// After the gather: the irradiance each patch receives through the clusters above it.
  void pushClusters();
  /// After push–pull: each cluster's R, largest R and intensity from its patches.
  void pullClusters();

  const Scene &scene_;
  const RayTracer &tracer_;
  RadiosityMesh &mesh_;
  DirectLightField &field_;
  const SolverOptions &options_;
  FaceTree faces_;
  LinkEstimator estimator_;
  ClusterTree clusters_;
  double minimumEdge_ = 0, threshold_ = 0;
  mutable tbb::task_arena arena_;
  // Per tree node.
  std::vector<Bands> reflectance_, emission_, reflected_, direct_;
  /// Translucent faces (transmission.h): τ per node, and the mean reflected
  /// irradiance (at a leaf its polynomial's mean, above the children's),
  /// which the other side's leaves read over the same region.
  std::vector<Bands> transmittance_, meanIrradiance_;
  /// direct_ and meanIrradiance_ as of the start of the sweep, what
  /// transmitted() reads: the patches are pushed and pulled in parallel, and
  /// one side must not read the other's while it is being written.
  std::vector<Bands> directBefore_, meanIrradianceBefore_;
  void keepForTransmission();
  /// Per patch of a translucent face: its face's other side (Face::twin), −1 if none.
  std::vector<int32_t> twinFace_;
  bool anyTranslucent_ = false;
  /// τ·H' at a leaf, direct and reflected parts: τ times the irradiance of
  /// the other side over the same region (0 for an opaque leaf), as of keepForTransmission.
  std::pair<Bands, Bands> transmitted(uint32_t leaf) const;
  /// What the oracles weigh an irradiance error by: max(ρ, τ) per band, since
  /// a translucent receiver passes τ of it to its other side.
  Bands scattering(uint32_t n) const;
  /// What each node's R polynomial misses of its children's (computeVariation), as of updateVariation.
  std::vector<Bands> variation_;
  /// R over each node as a polynomial in its parameters (mean: reflected_),
  /// and at the leaves H_direct's (directShape).
  std::vector<ReceiverPolynomial<Bands>> sourceShape_, directShape_;
  /// What each node gathered over its own links, and at the leaves all they received, as polynomials.
  std::vector<ReceiverPolynomial<Bands>> gathered_, irradiance_;
  /// At the leaves: 1, or 1/Σ_j F_ij where the links' form factors sum clearly past 1 (measureClosure).
  std::vector<float> closure_;
  std::vector<std::vector<uint32_t>> links_;  ///< incoming links (indices, see above)
  /// Deques, not vectors: growing one never copies it, so its peak memory
  /// is what it holds (a vector's doubling held 3× its links for a moment).
  std::deque<LinkRecord> records_;
  std::deque<ClusterLinkRecord> clusterRecords_;
  std::vector<uint32_t> newLeaves_;  ///< split since the direct light was last read
  size_t leaves_ = 0;
  size_t rays_ = 0;
  // Per cluster.
  std::vector<Bands> clusterReflectance_;                 ///< largest ρ of its patches (at least kLeastReflectance)
  std::vector<Bands> clusterReflected_, clusterLargest_;  ///< area mean and largest of its patches' R
  std::vector<HarmonicBands> clusterIntensity_;           ///< Σ R_i A_i·lobe(n_i) (large clusters)
  std::vector<HarmonicBands> clusterArea_;                ///< Σ A_i·lobe(n_i), every band alike
  std::vector<HarmonicBands> clusterField_;               ///< radiance gathered (large clusters)
  std::vector<HarmonicBands> clusterFieldBelow_;          ///< clusterField_ summed from the root down
  std::vector<int64_t> exactOffset_;                      ///< small clusters: offset into exactIrradiance_, else −1
  std::vector<Bands> exactIrradiance_;                    ///< small clusters: per patch of its range, gathered
  std::vector<std::vector<uint32_t>> clusterLinks_;       ///< incoming links, indices into clusterRecords_
  std::vector<Bands> patchClusterIrradiance_;             ///< per patch: what the clusters above it pushed down
};

}  // namespace radiant
