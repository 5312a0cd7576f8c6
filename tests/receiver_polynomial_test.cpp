// ReceiverPolynomial (radiosity/receiver_polynomial.h): the polynomials over a
// receiving node that hierarchical-exact gathers into and pushes down its
// trees. Everything here is exact algebra, so the tolerances are round-off:
// a few ulps of the values involved (|c| ≤ 1, parameters in [0, 1]).
#include "radiosity/receiver_polynomial.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/link_estimate.h"
#include "util/random.h"

namespace radiant {
namespace {

constexpr double kRoundOff = 1e-12;

ReceiverPolynomial<double> randomPolynomial(Pcg32 &rng, bool quad) {
  ReceiverPolynomial<double> p;
  for (int k = 0; k < 4; ++k) p.c[k] = 2 * rng.next() - 1;
  if (!quad) p.c[3] = 0;  // a triangle's polynomial is linear
  return p;
}

/// Random parameters of a node: the unit square, or the triangle b1, b2 ≥ 0, b1 + b2 ≤ 1.
std::array<double, 2> randomParameters(Pcg32 &rng, bool quad) {
  double u = rng.next(), v = rng.next();
  if (!quad && u + v > 1) u = 1 - u, v = 1 - v;
  return {u, v};
}

/// A tree node over a random polygon: a quad with its corners on a circle
/// (convex, planar, in general not a parallelogram), or a random triangle.
MeshTreeNode randomNode(Pcg32 &rng, bool quad) {
  MeshTreeNode n;
  n.vertexCount = quad ? 4 : 3;
  if (quad) {
    // Corners on a circle at increasing angles, in the plane z = 0.3: convex, not a parallelogram.
    double angle = 2 * kPi * rng.next();
    for (int k = 0; k < 4; ++k) {
      angle += 0.3 + 1.2 * rng.next();
      n.corners[k] = {std::cos(angle), std::sin(angle), 0.3};
    }
  } else {
    for (int k = 0; k < 3; ++k) n.corners[k] = {rng.next(), rng.next(), rng.next()};
  }
  return n;
}

/// The affine map from child `child`'s parameters to the parent's, derived
/// from the geometry of childCorners (mesh/tree_mesh.cpp), not copied from
/// restrictTo: each child corner is located among the parent's half-lattice
/// points (parameters in {0, ½, 1}) by position. Returns {o_u, o_v, a_uu,
/// a_uv, a_vu, a_vv}: (u, v) = o + A (u', v').
std::array<double, 6> childMap(const MeshTreeNode &parent, int child) {
  const bool quad = parent.vertexCount == 4;
  const auto children = childCorners(parent);
  auto parametersOf = [&](const Vec3 &p) {
    for (double u : {0.0, 0.5, 1.0})
      for (double v : {0.0, 0.5, 1.0}) {
        if (!quad && u + v > 1) continue;
        if (length(pointOn(parent, u, v) - p) < 1e-12) return std::array<double, 2>{u, v};
      }
    ADD_FAILURE() << "a child corner is not on the parent's half-lattice";
    return std::array<double, 2>{0, 0};
  };
  // Child parameters (0,0), (1,0) and (0,1) are its corners 0, 1 and (quad) 3 or (triangle) 2.
  const auto o = parametersOf(children[child][0]);
  const auto e1 = parametersOf(children[child][1]);
  const auto e2 = parametersOf(children[child][quad ? 3 : 2]);
  return {o[0], o[1], e1[0] - o[0], e2[0] - o[0], e1[1] - o[1], e2[1] - o[1]};
}

class ReceiverPolynomialShape : public ::testing::TestWithParam<bool> {};

TEST_P(ReceiverPolynomialShape, TheChildMapsFollowTheChildCornersGeometry) {
  // The derived maps are what pointOn says: the child's point at (u', v') is
  // the parent's at the mapped parameters (a bilinear quad restricted to an
  // axis-aligned sub-square is the bilinear map of its corners). Fails if
  // childCorners' layout or pointOn's parameterisation changed.
  const bool quad = GetParam();
  Pcg32 rng(11, 3);
  for (int trial = 0; trial < 20; ++trial) {
    MeshTreeNode parent = randomNode(rng, quad);
    const auto children = childCorners(parent);
    for (int c = 0; c < 4; ++c) {
      MeshTreeNode child = parent;
      child.corners = children[c];
      const auto m = childMap(parent, c);
      for (int k = 0; k < 10; ++k) {
        const auto [u, v] = randomParameters(rng, quad);
        const Vec3 expected = pointOn(parent, m[0] + m[2] * u + m[3] * v, m[1] + m[4] * u + m[5] * v);
        EXPECT_LT(length(pointOn(child, u, v) - expected), kRoundOff) << "child " << c;
      }
    }
  }
}

TEST_P(ReceiverPolynomialShape, RestrictToIsExact) {
  // For random coefficients, the child's polynomial at random child
  // parameters equals the parent's at the mapped parameters. Fails on any
  // wrong offset, scale or cross term in restrictTo (e.g. the middle
  // triangle's reflected map, or quad children in raster order 0,1,2,3 =
  // (0,0),(1,0),(0,1),(1,1) instead of tree_mesh.cpp's).
  const bool quad = GetParam();
  Pcg32 rng(5, 8);
  const MeshTreeNode parent = randomNode(rng, quad);
  for (int trial = 0; trial < 50; ++trial) {
    const ReceiverPolynomial<double> p = randomPolynomial(rng, quad);
    for (int c = 0; c < 4; ++c) {
      const auto m = childMap(parent, c);
      const ReceiverPolynomial<double> r = p.restrictTo(quad, c);
      if (!quad) {
        EXPECT_EQ(r.c[3], 0.0) << "a triangle's restriction stays linear";
      }
      for (int k = 0; k < 10; ++k) {
        const auto [u, v] = randomParameters(rng, quad);
        const double expected = p.value(m[0] + m[2] * u + m[3] * v, m[1] + m[4] * u + m[5] * v);
        EXPECT_NEAR(r.value(u, v), expected, kRoundOff) << "child " << c << " at " << u << ", " << v;
      }
    }
  }
}

TEST_P(ReceiverPolynomialShape, ChildrenMeansAverageToTheParentMean) {
  // The four children have a quarter of the parent's area each (quads split at
  // their bilinear midpoints, triangles at their edge midpoints), so the
  // parent's mean is the plain average of theirs: what push–pull relies on.
  // Fails if restrictTo or mean (quad ¼ weights on u, v; triangle ⅓) were off.
  const bool quad = GetParam();
  Pcg32 rng(9, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const ReceiverPolynomial<double> p = randomPolynomial(rng, quad);
    double sum = 0;
    for (int c = 0; c < 4; ++c) sum += p.restrictTo(quad, c).mean(quad);
    EXPECT_NEAR(sum / 4, p.mean(quad), kRoundOff);
  }
  // mean() itself: a bilinear function's mean over the square is its value at
  // the centre, a linear one's over the triangle its value at the centroid;
  // and the corners average to it too (quad: the four; triangle: the three).
  for (int trial = 0; trial < 20; ++trial) {
    const ReceiverPolynomial<double> p = randomPolynomial(rng, quad);
    if (quad) {
      EXPECT_NEAR(p.mean(true), p.value(0.5, 0.5), kRoundOff);
      EXPECT_NEAR(p.mean(true), (p.value(0, 0) + p.value(1, 0) + p.value(1, 1) + p.value(0, 1)) / 4, kRoundOff);
    } else {
      EXPECT_NEAR(p.mean(false), p.value(1.0 / 3, 1.0 / 3), kRoundOff);
      EXPECT_NEAR(p.mean(false), (p.value(0, 0) + p.value(1, 0) + p.value(0, 1)) / 3, kRoundOff);
    }
  }
}

TEST_P(ReceiverPolynomialShape, FitReproducesItsOwnSpaceAtTheRulePoints) {
  // Values of a bilinear (quad) / linear (triangle) function at the
  // receiverRule points are fitted exactly: the weighted least-squares fit
  // of a function in the basis' span is the function. Fails if the normal
  // matrix or the basis order (1, u, v, uv) were wrong.
  const bool quad = GetParam();
  const std::vector<CubaturePoint> &rule = receiverRule(quad);
  double weights = 0;
  for (const CubaturePoint &q : rule) weights += q.weight;
  EXPECT_NEAR(weights, 1.0, 1e-12);
  Pcg32 rng(2, 2);
  for (int trial = 0; trial < 50; ++trial) {
    const ReceiverPolynomial<double> f = randomPolynomial(rng, quad);
    std::vector<double> values;
    for (const CubaturePoint &q : rule) values.push_back(f.value(q.u, q.v));
    const ReceiverPolynomial<double> p = fitReceiverPolynomial(quad, values);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(p.c[k], f.c[k], 1e-11) << "coefficient " << k;
    for (const CubaturePoint &q : rule) EXPECT_NEAR(p.value(q.u, q.v), f.value(q.u, q.v), kRoundOff);
  }
}

TEST_P(ReceiverPolynomialShape, FitMeanIsTheRuleMeanForAnyValues) {
  // With the constant in the basis, the weighted residual sums to zero, and
  // the rule integrates the fitted polynomial exactly, so the fit's mean is
  // Σ w_k f_k whatever the values: a link's polynomial carries exactly its
  // cubature form factor. Fails for an unweighted fit or a fit without the
  // constant term.
  const bool quad = GetParam();
  const std::vector<CubaturePoint> &rule = receiverRule(quad);
  Pcg32 rng(4, 6);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> values;
    double ruleMean = 0;
    for (const CubaturePoint &q : rule) {
      values.push_back(rng.next() * (trial % 2 ? 1.0 : 1e-3) + (trial % 3 == 0 ? 1e3 : 0.0));
      ruleMean += q.weight * values.back();
    }
    const ReceiverPolynomial<double> p = fitReceiverPolynomial(quad, values);
    EXPECT_NEAR(p.mean(quad), ruleMean, 1e-12 * (1 + std::abs(ruleMean)));
  }
}

TEST_P(ReceiverPolynomialShape, FitChildMeansReproducesItsOwnSpace) {
  // A bilinear (quad) or linear (triangle) function's mean over each child is
  // its value at the child's centroid; fitChildMeans must give back the
  // function from those four means. Fails if the children's centres (quad
  // children in tree_mesh.cpp's order) or the triangle's least squares were wrong.
  const bool quad = GetParam();
  Pcg32 rng(7, 7);
  const MeshTreeNode parent = randomNode(rng, quad);
  for (int trial = 0; trial < 50; ++trial) {
    const ReceiverPolynomial<double> f = randomPolynomial(rng, quad);
    std::array<double, 4> means;
    for (int c = 0; c < 4; ++c) {
      // The child's mean by the child's own (exact) mean, through the map derived from the geometry.
      const auto m = childMap(parent, c);
      const double cu = quad ? 0.5 : 1.0 / 3, cv = quad ? 0.5 : 1.0 / 3;  // the child's centroid
      means[c] = f.value(m[0] + m[2] * cu + m[3] * cv, m[1] + m[4] * cu + m[5] * cv);
      EXPECT_NEAR(means[c], f.restrictTo(quad, c).mean(quad), kRoundOff);
    }
    const ReceiverPolynomial<double> p = fitChildMeans(quad, means);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(p.c[k], f.c[k], 1e-11) << "coefficient " << k;
  }
}

TEST_P(ReceiverPolynomialShape, FitChildMeansKeepsTheMeanForAnyMeans) {
  // Whatever the children's means, the fitted polynomial's mean is their
  // average (the parent's mean, each child being a quarter). Fails if the
  // triangle's constant were fitted without the mean constraint.
  const bool quad = GetParam();
  Pcg32 rng(3, 9);
  for (int trial = 0; trial < 50; ++trial) {
    std::array<double, 4> means;
    for (double &m : means) m = rng.next();
    const ReceiverPolynomial<double> p = fitChildMeans(quad, means);
    EXPECT_NEAR(p.mean(quad), (means[0] + means[1] + means[2] + means[3]) / 4, kRoundOff);
    if (!quad) {
      EXPECT_EQ(p.c[3], 0.0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ReceiverPolynomial, ReceiverPolynomialShape, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool> &info) { return info.param ? "Quad" : "Triangle"; });

TEST(ReceiverPolynomial, BandsAndDoublesAgree) {
  // The solver uses ReceiverPolynomial<Bands>: each band must behave as the
  // double polynomial of its coefficients (restrictTo, value, mean).
  Pcg32 rng(1, 1);
  for (bool quad : {true, false}) {
    ReceiverPolynomial<Bands> b;
    std::array<ReceiverPolynomial<double>, kBandCount> d;
    for (int k = 0; k < 4; ++k)
      for (int band = 0; band < kBandCount; ++band) {
        d[band].c[k] = quad || k < 3 ? rng.next() : 0.0;
        b.c[k][band] = d[band].c[k];
      }
    for (int c = 0; c < 4; ++c) {
      const ReceiverPolynomial<Bands> rb = b.restrictTo(quad, c);
      for (int band = 0; band < kBandCount; ++band) {
        const ReceiverPolynomial<double> rd = d[band].restrictTo(quad, c);
        EXPECT_EQ(rb.value(0.3, 0.2)[band], rd.value(0.3, 0.2));
        EXPECT_EQ(rb.mean(quad)[band], rd.mean(quad));
      }
    }
  }
}

}  // namespace
}  // namespace radiant
