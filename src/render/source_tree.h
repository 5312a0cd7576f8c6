// The solution's elements as light sources in one binary tree, for gathering
// at a point from a cut of it (reichert: C&W §9.3.1, at the cost of the
// hierarchy instead of the element count).
//
// Every element of positive radiosity is a leaf; a node holds the power of
// its elements (Φ = Σ B_j A_j), their bounding box and the cone of their
// normals. At a receiving point x the irradiance from a node's elements is
// bounded by
//   H ≤ Φ · max cos θ_x · max cos θ_j / (π d²),
// d the distance from x to the box (Walter et al., "Lightcuts", SIGGRAPH
// 2005, §4: the bound for a cluster of oriented lights). A cut is chosen by
// splitting the node of largest bound until every bound is a small fraction
// of the gathered estimate or the cut has its size: near, bright and large
// nodes go down to their elements, far and dim ones stay whole. A node of the
// cut is estimated from one of its elements, drawn with probability
// ∝ B_j A_j (as stochastic lightcuts do: Yuksel, "Stochastic Lightcuts",
// HPG 2019), its exact point-to-polygon factor and visibility scaled by
// Φ / (B_j A_j): unbiased for the node's sum, so the cut's sum is unbiased for
// Reichert's gather over every element, and no element is ever left out.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/solution.h"
#include "util/math.h"

namespace radiant {

class SourceTree {
 public:
  /// Built over the mesh's elements of positive `radiosity` (one value per
  /// element: what each sends out, W·m⁻², e.g. only its emission).
  SourceTree(const RadiosityMesh &mesh, const std::vector<Bands> &radiosity);
  /// Built over `solution`'s elements of positive display radiosity (ambient included).
  explicit SourceTree(const Solution &solution);

  /// A node of a cut: its index, and its share of the cut's unoccluded estimate.
  struct CutNode {
    uint32_t node = 0;
    bool leaf = false;
  };

  /// What a gather costs besides its cut's nodes (each a form factor and a
  /// shadow ray), counted where asked: the tests' measure of work that must
  /// not grow with the element count.
  struct Work {
    long splits = 0;  ///< nodes opened while choosing cuts (two bounds each)
    long levels = 0;  ///< levels descended while drawing elements (two importances each)
  };

  /// The cut for a receiving point x with normal n (the side that gathers):
  /// nodes whose elements together are all that can light x, split while a
  /// node's bound exceeds `relativeError` of the unoccluded estimate of the
  /// whole and the cut has fewer than `maxNodes`. relativeError 0: every element.
  void chooseCut(const Vec3 &x, const Vec3 &n, double relativeError, int maxNodes, std::vector<CutNode> &cut,
                 Work *work = nullptr) const;

  /// One element of a node, drawn from u in [0, 1) by descending the tree,
  /// at each fork with probability ∝ each child's importance for x (normal n):
  /// its power times the bounds of both cosines over the squared distance to
  /// its centre, that distance at least half its box's diagonal (Conty
  /// Estevez & Kulla, "Importance Sampling of Many Lights with Adaptive
  /// Tree Splitting", HPG 2018). Once the descent reaches a node far from x
  /// for its size whose normals are close, the importance varies little
  /// among its elements, and one is drawn ∝ power from the prefix sums of
  /// the elements in tree order (a binary search, not a descent that
  /// evaluates two bounds a level): the cost of a draw stops growing with the
  /// depth. `probability` is the chance of drawing it.
  uint32_t drawElement(uint32_t node, const Vec3 &x, const Vec3 &n, double u, double &probability,
                       Work *work = nullptr) const;

  size_t nodeCount() const { return nodes_.size(); }
  bool empty() const { return nodes_.empty(); }

 private:
  struct Node {
    Vec3 lo, hi;        ///< bounding box of the elements' polygons
    Vec3 sphereCentre;  ///< the box's bounding sphere, for the bounds
    double radius = 0;
    Vec3 axis;             ///< the normal cone: every normal within the half-angle of axis
    double cosSpread = 1;  ///< cos and sin of the half-angle; cos −1: any direction
    double sinSpread = 0;
    Vec3 centre;        ///< power-weighted centre, for the unoccluded estimate
    double power = 0;   ///< Σ A_j B̄_j, B̄ the band average, W
    uint32_t left = 0;  ///< children; a leaf has left == right == its element
    uint32_t right = 0;
    uint32_t first = 0;  ///< its elements are order_[first, first + count)
    uint32_t count = 0;
    bool leaf = false;
  };
  /// Draws one of the node's elements ∝ power (the prefix sums), multiplying `probability` by its chance.
  uint32_t drawByPower(const Node &node, double u, double &probability) const;
  /// An upper bound of cos θ_x · cos θ_j over the node's elements seen from x (normal n).
  double cosineBound(const Node &node, const Vec3 &x, const Vec3 &n) const;
  /// An upper bound of the irradiance the node's elements give x (normal n).
  double bound(const Node &node, const Vec3 &x, const Vec3 &n) const;
  /// The importance of a node for x, for drawing elements (drawElement).
  double importance(const Node &node, const Vec3 &x, const Vec3 &n) const;
  /// A point estimate of it, the node's power from its centre, no visibility.
  double estimate(const Node &node, const Vec3 &x, const Vec3 &n) const;
  uint32_t build(std::vector<uint32_t> &elements, size_t begin, size_t end, const RadiosityMesh &mesh,
                 const std::vector<double> &power, const std::vector<Vec3> &lo, const std::vector<Vec3> &hi);

  std::vector<Node> nodes_;
  uint32_t root_ = 0;
  std::vector<uint32_t> order_;       ///< the elements in tree order: a node's are contiguous
  std::vector<double> powerThrough_;  ///< Σ power of order_[0..k], inclusive
};

}  // namespace radiant
