// The form factor of a hierarchical link, with what the refinement oracle
// needs: for a receiver node r and a source node s (tree nodes of two
// patches), F(r ← s) as polynomials over r (one per term of the source's
// radiosity polynomial, receiver_polynomial.h), how much the point factor
// strays from them, and the visibility.
//
// At each of the receiver's cubature points x_k: F(x_k → the part of s that
// x_k sees), exact — Lambert's contour integral (form_factor.h) over the
// source, or, when the shaft between the two nodes (the convex hull of their
// corners) holds other faces, over what backprojection leaves of it past
// them (backprojection.h) — and the kernel-weighted means of the source's
// parameters seen from x_k, so that a source whose radiosity varies
// linearly is gathered to second order. No shadow rays: a link's form
// factor has no noise, and the spread the oracle reads is not a coin toss
// (with a few rays per link, links whose rays all agreed were taken as
// wholly visible or hidden, and the hidden side won: the Cornell box's
// reflected light came out 1 % dark).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/receiver_polynomial.h"
#include "raytrace/face_tree.h"
#include "scene/scene.h"

namespace radiant {

struct LinkEstimate {
  double formFactor = 0;  ///< F(receiver ← source), area mean over the receiver, visibility included
  /// The form factor as a polynomial over the receiver (its mean is
  /// formFactor), and where on the source the coupling lies: the
  /// kernel-weighted mean of the source's parameters (u, v) seen from the
  /// receiver's centre. A link carries shape × R(moments), the source's
  /// radiosity polynomial evaluated there without its bilinear term, which
  /// gathers a source whose R varies linearly to second order (measured,
  /// the bilinear term made the Cornell box 0.1–0.3 % darker at every
  /// --quality).
  ReceiverPolynomial<float> shape;
  std::array<float, 2> moments{0.5f, 0.5f};
  /// max over cubature points |F_k − shape(x_k)|: what the polynomial misses (visibility included)
  double spread = 0;
  int rays = 0;  ///< backprojections (cubature points with faces in the shaft)
  /// F(x_k → the visible part of the source) at the receiver's cubature points.
  std::array<double, 9> pointFactors{};
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

class RayTracer;

class LinkEstimator {
 public:
  /// `faces` must be built over `scene`. With `tracer`, a link whose shaft
  /// holds more than kMaxExactOccluders faces (a tessellated model between
  /// the two nodes) has its visibility sampled instead of subtracted: at
  /// each cubature point, the exact unoccluded factor times the
  /// kernel-weighted fraction of a fixed grid of kVisibilityGrid² points on
  /// the source that the point sees; `spread` then also holds how far those
  /// rays could be off, so the oracle refines such links until they carry
  /// little.
  LinkEstimator(const Scene &scene, const FaceTree &faces, const RayTracer *tracer = nullptr);
  static constexpr size_t kMaxExactOccluders = 48;
  static constexpr int kVisibilityGrid = 4;

  /// F(receiver ← source), deterministic: its form factor, spread and
  /// shape[0] (what the refinement decides by). `knownClear`: a parent pair's
  /// shaft was clear, so this one is too.
  LinkEstimate estimate(const LinkEnd &receiver, const LinkEnd &source, bool knownClear) const;
  /// The moments, for a link that is kept.
  void completeShape(const LinkEnd &receiver, const LinkEnd &source, LinkEstimate &estimate) const;
  /// The faces with area inside the convex hull of the two nodes' corners,
  /// other than the nodes' own faces: all that may stand between them.
  /// False (and `out` incomplete) when the hull holds more than `limit` faces.
  bool shaftOccluders(const LinkEnd &receiver, const LinkEnd &source, std::vector<uint32_t> &out,
                      size_t limit = SIZE_MAX) const;

 private:
  /// The kernel-weighted fraction of the source's grid points x sees, and
  /// how far that may be off.
  double sampledVisibility(const Vec3 &x, const Vec3 &n, const LinkEnd &source, double &uncertainty) const;

  const Scene &scene_;
  const FaceTree &faces_;
  const RayTracer *tracer_ = nullptr;
  double scale_ = 1;
};

/// Where the source moments are taken: 2 × 2 Gauss–Legendre on a quad
/// (exact for degree 3), the edge midpoints on a triangle (degree 2).
const std::vector<CubaturePoint> &momentRule(bool quad);
/// The point of a node at parameters (u, v): bilinear on a quad, barycentric
/// (b1, b2) on a triangle.
Vec3 pointOn(const MeshTreeNode &n, double u, double v);
/// Kernel-weighted means of the source's u and v seen from x (normal n);
/// the centre's parameters when the source is edge-on from x.
std::array<double, 2> sourceMoments(const Vec3 &x, const Vec3 &n, const MeshTreeNode &source, const Vec3 &sourceNormal);

}  // namespace radiant
