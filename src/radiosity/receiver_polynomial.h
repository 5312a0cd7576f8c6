// Light gathered over a receiving node as a low-order polynomial, not a
// constant: bilinear in a quad's parameters (u, v), linear in a triangle's
// barycentrics (b1, b2).
//
// Hierarchical radiosity gathers at every level of a tree and pushes what a
// node gathered down to its leaves. With a constant per link (Hanrahan et
// al. 1991), a leaf at the edge of a large receiver gets the receiver's mean
// form factor from every coarse link; the errors of hundreds of links in a
// leaf's chain add up (±10 % in a furnace where the exact answer is uniform).
// A polynomial fitted to the point-to-source form factors at the receiver's
// cubature points keeps the first-order variation, and restricting it to a
// child is exact, so a leaf receives what its own part of the receiver does
// to second order (in the spirit of Galerkin radiosity with a higher-order
// basis on the receiver: Zatz 1993; Gortler, Schröder, Cohen & Hanrahan 1993).
#pragma once

#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "util/spectrum.h"

namespace radiant {

/// A point of a receiver's cubature rule, in its parameters: (u, v) on a
/// quad's square, barycentrics (b1, b2) on a triangle; weights sum to 1.
struct CubaturePoint {
  double u, v, weight;
};

/// f(u, v) = c0 + c1·u + c2·v + c3·u·v (a triangle's c3 is 0).
template <typename T>
struct ReceiverPolynomial {
  std::array<T, 4> c{};

  ReceiverPolynomial &operator+=(const ReceiverPolynomial &o) {
    for (int k = 0; k < 4; ++k) c[k] += o.c[k];
    return *this;
  }
  T value(double u, double v) const { return c[0] + c[1] * u + c[2] * v + c[3] * (u * v); }
  /// The mean over the node: over the unit square, or over the triangle.
  T mean(bool quad) const {
    return quad ? c[0] + c[1] * 0.5 + c[2] * 0.5 + c[3] * 0.25 : c[0] + (c[1] + c[2]) * (1.0 / 3);
  }

  /// The same function in the parameters of child `child` (mesh/tree_mesh.cpp's
  /// layout: quads (0,0), (1,0), (1,1), (0,1); triangles the corners at
  /// vertex 0, 1, 2, then the middle one), exactly.
  ReceiverPolynomial restrictTo(bool quad, int child) const {
    ReceiverPolynomial r;
    if (quad) {
      // u = ou + u'/2, v = ov + v'/2.
      static constexpr double offset[4][2] = {{0, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
      const double ou = offset[child][0], ov = offset[child][1];
      r.c[0] = c[0] + c[1] * ou + c[2] * ov + c[3] * (ou * ov);
      r.c[1] = (c[1] + c[3] * ov) * 0.5;
      r.c[2] = (c[2] + c[3] * ou) * 0.5;
      r.c[3] = c[3] * 0.25;
      return r;
    }
    // (b1, b2) as affine functions of the child's (b1', b2').
    static constexpr double map[4][6] = {
        // b1 = m0 + m1 b1' + m2 b2', b2 = m3 + m4 b1' + m5 b2'
        {0, 0.5, 0, 0, 0, 0.5},       // corner at vertex 0
        {0.5, 0.5, 0, 0, 0, 0.5},     // corner at vertex 1
        {0, 0.5, 0, 0.5, 0, 0.5},     // corner at vertex 2
        {0.5, 0, -0.5, 0, 0.5, 0.5},  // middle (mab, mbc, mac)
    };
    const double *m = map[child];
    r.c[0] = c[0] + c[1] * m[0] + c[2] * m[3];
    r.c[1] = c[1] * m[1] + c[2] * m[4];
    r.c[2] = c[1] * m[2] + c[2] * m[5];
    r.c[3] = c[3] * 0.0;
    return r;
  }
};

/// The polynomial through four children's means (taken at the children's
/// centres; a triangle's by least squares through its four), whose mean is
/// the parent's mean: how a node's radiosity varies over it, from its children.
template <typename T>
ReceiverPolynomial<T> fitChildMeans(bool quad, const std::array<T, 4> &m) {
  ReceiverPolynomial<T> p;
  if (quad) {
    // The bilinear through the centres (¼,¼), (¾,¼), (¾,¾), (¼,¾).
    const T a = m[0], b = m[1] - m[0], c = m[3] - m[0], d = m[0] - m[1] + m[2] - m[3];
    p.c[0] = a - b * 0.5 - c * 0.5 + d * 0.25;
    p.c[1] = b * 2.0 - d;
    p.c[2] = c * 2.0 - d;
    p.c[3] = d * 4.0;
    return p;
  }
  // Centroids (⅙,⅙), (⅔,⅙), (⅙,⅔), (⅓,⅓): least squares for a + b·b1 + c·b2,
  // whose normal equations reduce to b = 2(m1 − m0), c = 2(m2 − m0), and a
  // from the mean (the centroids average to the parent's, ⅓, ⅓).
  p.c[1] = (m[1] - m[0]) * 2.0;
  p.c[2] = (m[2] - m[0]) * 2.0;
  p.c[0] = (m[0] + m[1] + m[2] + m[3]) * 0.25 - (p.c[1] + p.c[2]) * (1.0 / 3);
  return p;
}

/// Receiver cubature: 3 × 3 Gauss–Legendre on a quad's square (exact for
/// degree 5), Dunavant's degree-4 six-point rule on a triangle.
const std::vector<CubaturePoint> &receiverRule(bool quad);

/// The weighted least-squares polynomial through values at the rule's points.
ReceiverPolynomial<double> fitReceiverPolynomial(bool quad, std::span<const double> values);

}  // namespace radiant
