// The form factor of a hierarchical link, with what the refinement oracle
// needs: for a receiver node r and a source node s (tree nodes of two
// patches), F(r ← s) as polynomials over r (one per term of the source's
// radiosity polynomial, receiver_polynomial.h), how much the point factor
// strays from them, and the visibility.
//
// At each of the receiver's cubature points x_k: Lambert's contour integral
// F(x_k → s), exact and unoccluded (form_factor.h); the kernel-weighted means
// of the source's parameters seen from x_k (so that a source whose radiosity
// varies linearly is gathered to second order); and, unless the shaft
// between the two (the convex hull of their corners) holds no other face,
// one shadow ray to a stratified point of the source, weighted by the kernel
// of the piece it stands for (the near parts of a source dominate its form
// factor). A link with a clear shaft is exactly unoccluded and casts no ray.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/receiver_polynomial.h"
#include "raytrace/face_tree.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

struct LinkEstimate {
  double formFactor = 0;   ///< F(receiver ← source), area mean over the receiver, visibility included
  /// The coupling as polynomials over the receiver, one per term of the
  /// source's radiosity polynomial (1, u, v, uv): what the receiver at (u, v)
  /// gathers from a source whose R is that term, so a link carries
  /// Σ_j R_j·shape[j] (shape[0]'s mean is formFactor).
  std::array<ReceiverPolynomial<float>, 4> shape;
  /// max over cubature points |F_k − shape(x_k)|: what the polynomial misses (visibility included)
  double spread = 0;
  double visibleFraction = 1;
  double visibility = 1;  ///< kernel-weighted visible fraction: formFactor over the unoccluded one
  int rays = 0;
  /// The convex hull of the two nodes holds no other face: nothing can block
  /// between them, nor between any of their children.
  bool clearShaft = false;
};


/// One side of a link: a tree node, its patch's front normal and scene face.
struct LinkEnd {
  const MeshTreeNode &node;
  Vec3 normal;
  uint32_t face;
};

class LinkEstimator {
 public:
  /// `faces` must be built over the same scene as `tracer`.
  LinkEstimator(const RayTracer &tracer, const FaceTree &faces, uint64_t seed);

  /// F(receiver ← source). `key` seeds its shadow rays (deterministic);
  /// `knownClear`: a parent pair's shaft was clear, so this one is too.
  LinkEstimate estimate(const LinkEnd &receiver, const LinkEnd &source, uint64_t key, bool knownClear) const;
  /// True when the convex hull of the two nodes' corners may hold another
  /// face (one with area inside it, other than the two nodes' own faces).
  bool shaftMayBeBlocked(const LinkEnd &receiver, const LinkEnd &source) const;

 private:
  const RayTracer &tracer_;
  const Scene &scene_;
  const FaceTree &faces_;
  uint64_t seed_ = 1;
  double scale_ = 1;
};

/// Where the source moments are taken: 2 × 2 Gauss–Legendre on a quad
/// (exact for degree 3), the edge midpoints on a triangle (degree 2).
const std::vector<CubaturePoint> &momentRule(bool quad);
/// The point of a node at parameters (u, v): bilinear on a quad, barycentric
/// (b1, b2) on a triangle.
Vec3 pointOn(const MeshTreeNode &n, double u, double v);
/// Kernel-weighted means of the source's u, v and uv seen from x (normal n);
/// the centre's parameters when the source is edge-on from x.
std::array<double, 3> sourceMoments(const Vec3 &x, const Vec3 &n, const MeshTreeNode &source, const Vec3 &sourceNormal);

}  // namespace radiant
