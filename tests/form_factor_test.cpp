// Form factors against closed forms (Howell's catalogue; docs/radiosity.md,
// Form factors): the exact contour integral, the ray-cast disc estimator and
// the hemicube.
//
// Tolerances: exact formulas are compared to 1e-6 (the closed-form values
// are quoted to 6–7 digits) or to round-off where two exact expressions must
// agree; quadratures to what their rule reaches (checked by refining it);
// Monte Carlo and hemicube results to bounds derived or measured below.
#include "radiosity/form_factor.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "radiosity/hemicube.h"
#include "test_scenes.h"
#include "util/fast_angle.h"
#include "util/random.h"

namespace radiant {
namespace {

// ---------------------------------------------------------------------------
// Closed forms (Howell C-11, C-14, B-3; Lambert's contour integral)

/// Two parallel, directly opposed a × b rectangles at distance c (Howell C-11).
double formFactorParallelRectangles(double a, double b, double c) {
  const double x = a / c, y = b / c;
  return 2 / (kPi * x * y) *
         (0.5 * std::log((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)) +
          x * std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)) +
          y * std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) - x * std::atan(x) - y * std::atan(y));
}

/// From a w × l rectangle to an h × l rectangle perpendicular to it along the common edge l (Howell C-14).
double formFactorPerpendicularRectangles(double w, double h, double l) {
  const double W = w / l, H = h / l, S = W * W + H * H;
  const double a = W * std::atan(1 / W) + H * std::atan(1 / H) - std::sqrt(S) * std::atan(1 / std::sqrt(S));
  const double logTerm = std::log((1 + W * W) * (1 + H * H) / (1 + S)) +
                         W * W * std::log(W * W * (1 + S) / ((1 + W * W) * S)) +
                         H * H * std::log(H * H * (1 + S) / ((1 + H * H) * S));
  return (a + 0.25 * logTerm) / (kPi * W);
}

/// Differential area parallel to an a × b rectangle at distance c, under one corner (Howell B-3).
double formFactorPointUnderCorner(double a, double b, double c) {
  const double x = a / c, y = b / c;
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
         (2 * kPi);
}

/// Coaxial parallel disc of radius r at distance h.
double formFactorCoaxialDisc(double r, double h) {
  return r * r / (r * r + h * h);
}

// ---------------------------------------------------------------------------
// Quadrature

/// A 1-D rule on an interval: nodes and weights.
struct Rule {
  std::vector<double> x, w;
};

/// Gauss–Legendre rule of order m on [a, b] (Newton on P_m; exact to degree 2m − 1).
void appendGaussLegendre(int m, double a, double b, Rule &rule) {
  for (int i = 0; i < m; ++i) {
    double t = std::cos(kPi * (i + 0.75) / (m + 0.5)), derivative = 0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = t;
      for (int k = 2; k <= m; ++k) {
        const double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = m * (t * p1 - p0) / (t * t - 1);
      const double step = p1 / derivative;
      t -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.x.push_back(0.5 * (a + b) + 0.5 * (b - a) * t);
    rule.w.push_back((b - a) / ((1 - t * t) * derivative * derivative));
  }
}

/// Composite Gauss–Legendre over [0, length] on the given break points (relative, 0…1).
Rule compositeRule(const std::vector<double> &breaks, int order, double length) {
  Rule rule;
  for (size_t k = 0; k + 1 < breaks.size(); ++k)
    appendGaussLegendre(order, breaks[k] * length, breaks[k + 1] * length, rule);
  return rule;
}

std::vector<double> uniformBreaks(int panels) {
  std::vector<double> b;
  for (int k = 0; k <= panels; ++k) b.push_back(static_cast<double>(k) / panels);
  return b;
}

/// Geometric mesh graded towards 0 (ratio `q`, `levels` panels), and towards
/// both ends when `bothEnds`: for integrands whose derivative blows up at the
/// edge a perpendicular surface shares (F(dA → A) ~ ½ − c·s·log s there).
std::vector<double> gradedBreaks(int levels, double q, bool bothEnds) {
  std::vector<double> half{0};
  const double end = bothEnds ? 0.5 : 1.0;
  for (int k = levels - 1; k >= 1; --k) half.push_back(end * std::pow(q, k));
  half.push_back(end);
  if (!bothEnds) return half;
  std::vector<double> all = half;
  for (int k = static_cast<int>(half.size()) - 2; k >= 0; --k) all.push_back(1 - half[k]);
  return all;
}

/// A planar rectangle origin + u·e1 + v·e2 (u, v ∈ [0,1]) with unit normal.
struct Rect {
  Vec3 origin, e1, e2;
  Vec3 normal() const { return normalize(cross(e1, e2)); }
  double area() const { return length(cross(e1, e2)); }
  std::array<Vec3, 4> corners() const { return {origin, origin + e1, origin + e1 + e2, origin + e2}; }
};

/// A_receiver · F(receiver → source) = ∫_receiver F(dA → source) dA, by a product rule.
double integratedFormFactor(const Rect &receiver, const Rect &source, const Rule &ruleU, const Rule &ruleV) {
  const auto polygon = source.corners();
  const Vec3 n = receiver.normal();
  const double l1 = length(receiver.e1), l2 = length(receiver.e2);
  double sum = 0;
  for (size_t i = 0; i < ruleU.x.size(); ++i)
    for (size_t j = 0; j < ruleV.x.size(); ++j) {
      const Vec3 p = receiver.origin + receiver.e1 * (ruleU.x[i] / l1) + receiver.e2 * (ruleV.x[j] / l2);
      sum += ruleU.w[i] * ruleV.w[j] * formFactorPointToPolygon(p, n, polygon);
    }
  return sum;
}

// The unit cube [0,1]³ seen from its floor (z = 0, normal +z).
const Rect kFloor{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
const Rect kCeiling{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};  // normal −z
const Rect kWallX0{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};   // x = 0 (shares the floor's edge u = 0)

// ---------------------------------------------------------------------------
// Closed forms themselves

TEST(FormFactorClosedForm, ReproduceReferenceTables) {
  EXPECT_NEAR(formFactorParallelRectangles(1, 1, 1), 0.1998249, 1e-6);
  EXPECT_NEAR(formFactorParallelRectangles(1, 1, 0.5), 0.415253, 1e-6);
  EXPECT_NEAR(formFactorParallelRectangles(1, 1, 2), 0.068590, 1e-6);
  EXPECT_NEAR(formFactorParallelRectangles(2, 1, 1), 0.285875, 1e-6);
  EXPECT_NEAR(formFactorParallelRectangles(10, 10, 1), 0.826995, 1e-6);
  EXPECT_NEAR(formFactorParallelRectangles(0.1, 0.1, 1), 0.003162, 1e-6);
  EXPECT_NEAR(formFactorParallelRectangles(1, 1.5, 0.5), 0.4756, 5e-5);  // EES example, 4 digits
  EXPECT_NEAR(formFactorPerpendicularRectangles(1, 1, 1), 0.2000438, 1e-6);
  EXPECT_NEAR(formFactorPerpendicularRectangles(1, 2, 1), 0.232853, 1e-6);
  EXPECT_NEAR(formFactorPerpendicularRectangles(2, 1, 1), 0.116426, 1e-6);
  EXPECT_NEAR(formFactorPerpendicularRectangles(1, 1, 2), 0.240636, 1e-6);
  EXPECT_NEAR(formFactorPerpendicularRectangles(0.5, 1, 1), 0.292373, 1e-6);
  // Cube sum rule in closed form (to 1e-9; docs/radiosity.md).
  EXPECT_NEAR(formFactorParallelRectangles(1, 1, 1) + 4 * formFactorPerpendicularRectangles(1, 1, 1), 1.0, 1e-9);
}

// ---------------------------------------------------------------------------
// Point to polygon: Lambert's contour integral

TEST(FormFactorPointToPolygon, PointUnderUnitSquare) {
  const std::array<Vec3, 4> square{Vec3{-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}};
  const double centre = formFactorPointToPolygon({0, 0, 0}, {0, 0, 1}, square);
  EXPECT_NEAR(centre, 0.239456, 1e-6);
  EXPECT_NEAR(centre, 4 * formFactorPointUnderCorner(0.5, 0.5, 1), 1e-14);
  const double corner = formFactorPointToPolygon({-0.5, -0.5, 0}, {0, 0, 1}, square);
  EXPECT_NEAR(corner, 0.138532, 1e-6);
  EXPECT_NEAR(corner, formFactorPointUnderCorner(1, 1, 1), 1e-14);
}

TEST(FormFactorPointToPolygon, HemicubeFacesCoverTheHemisphere) {
  const Vec3 p{0, 0, 0}, n{0, 0, 1};
  const std::array<Vec3, 4> top{Vec3{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  // A full side face z ∈ [−1,1]: clipping must leave exactly the upper half.
  const std::array<Vec3, 4> fullSide{Vec3{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}};
  const std::array<Vec3, 4> halfSide{Vec3{-1, 1, 0}, {1, 1, 0}, {1, 1, 1}, {-1, 1, 1}};
  const double fTop = formFactorPointToPolygon(p, n, top), fSide = formFactorPointToPolygon(p, n, halfSide);
  EXPECT_NEAR(fTop, 0.554126, 1e-6);
  EXPECT_NEAR(fSide, 0.111468, 1e-6);
  EXPECT_NEAR(formFactorPointToPolygon(p, n, fullSide), fSide, 1e-15);
  EXPECT_NEAR(fTop + 4 * fSide, 1.0, 1e-14);  // the five faces tile the hemisphere exactly
}

TEST(FormFactorPointToPolygon, CoaxialDiscAs256Gon) {
  // A regular N-gon inscribed in the disc of radius R contains the disc of its
  // inradius R cos(π/N), so F(disc(R cos π/N)) ≤ F(N-gon) ≤ F(disc(R)): the
  // tolerance is the area deficit's share of F, ≈ 3.8e-5 here.
  const int sides = 256;
  const double radius = 1, height = 1;
  std::vector<Vec3> polygon;
  for (int k = 0; k < sides; ++k) {
    const double phi = 2 * kPi * k / sides;
    polygon.push_back({radius * std::cos(phi), radius * std::sin(phi), height});
  }
  const double f = formFactorPointToPolygon({0, 0, 0}, {0, 0, 1}, polygon);
  const double upper = formFactorCoaxialDisc(radius, height);  // 0.5
  const double lower = formFactorCoaxialDisc(radius * std::cos(kPi / sides), height);
  EXPECT_NEAR(upper, 0.5, 1e-15);
  EXPECT_LE(f, upper);
  EXPECT_GE(f, lower);
  EXPECT_LT(upper - lower, 4e-5);
}

TEST(FormFactorPointToPolygon, IndependentOfWindingAndStartVertex) {
  Pcg32 rng(11, 3);
  for (int trial = 0; trial < 200; ++trial) {
    // A random planar pentagon, star-shaped about its centre, mostly above the
    // tangent plane of a randomly tilted point normal (some get clipped).
    const Vec3 centre{rng.next() * 2 - 1, rng.next() * 2 - 1, 0.5 + rng.next()};
    const Frame frame = Frame::fromNormal(normalize(Vec3{rng.next() - 0.5, rng.next() - 0.5, 1}));
    std::vector<Vec3> polygon;
    for (int k = 0; k < 5; ++k) {
      const double phi = 2 * kPi * (k + 0.8 * rng.next()) / 5, r = 0.2 + 0.3 * rng.next();
      polygon.push_back(centre + frame.toWorld({r * std::cos(phi), r * std::sin(phi), 0}));
    }
    const Vec3 n = normalize(Vec3{rng.next() - 0.5, rng.next() - 0.5, 1.5});
    const double f = formFactorPointToPolygon({0, 0, 0}, n, polygon);
    std::vector<Vec3> reversed(polygon.rbegin(), polygon.rend());
    std::vector<Vec3> rotated(polygon.begin() + 2, polygon.end());
    rotated.insert(rotated.end(), polygon.begin(), polygon.begin() + 2);
    EXPECT_GE(f, 0);
    EXPECT_NEAR(formFactorPointToPolygon({0, 0, 0}, n, reversed), f, 1e-14);
    EXPECT_NEAR(formFactorPointToPolygon({0, 0, 0}, n, rotated), f, 1e-14);
    // Additivity: the fan of triangles from the centre (the pentagon is star-
    // shaped about it) sums to the pentagon, so the terms' signs agree.
    double fan = 0;
    for (int k = 0; k < 5; ++k) {
      const std::array<Vec3, 3> triangle{centre, polygon[k], polygon[(k + 1) % 5]};
      fan += formFactorPointToPolygon({0, 0, 0}, n, triangle);
    }
    EXPECT_NEAR(fan, f, 1e-13);
  }
}

TEST(FormFactorPointToPolygon, ClippingKeepsOnlyTheFrontPart) {
  const Vec3 p{0, 0, 0}, n{0, 0, 1};
  // A wall x = 1 from z = −1 to z = 1 straddles the tangent plane z = 0.
  const std::array<Vec3, 4> straddling{Vec3{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}};
  const std::array<Vec3, 4> frontPart{Vec3{1, -1, 0}, {1, 1, 0}, {1, 1, 1}, {1, -1, 1}};
  const double f = formFactorPointToPolygon(p, n, frontPart);
  EXPECT_GT(f, 0.05);
  EXPECT_NEAR(formFactorPointToPolygon(p, n, straddling), f, 1e-15);
  // A tilted triangle cut into a quadrilateral: compare with the hand-clipped piece.
  const std::array<Vec3, 3> tilted{Vec3{-1, 0.5, -1}, {1, 0.5, 1}, {-1, 2, 1}};
  // The edges (v0,v1) and (v2,v0) cross z = 0 at their midpoints.
  const std::array<Vec3, 4> tiltedFront{Vec3{0, 0.5, 0}, {1, 0.5, 1}, {-1, 2, 1}, {-1, 1.25, 0}};
  EXPECT_NEAR(formFactorPointToPolygon(p, n, tilted), formFactorPointToPolygon(p, n, tiltedFront), 1e-15);
  // Entirely behind: exactly zero, also for the reversed normal's mirror case.
  const std::array<Vec3, 4> behind{Vec3{-0.5, -0.5, -1}, {0.5, -0.5, -1}, {0.5, 0.5, -1}, {-0.5, 0.5, -1}};
  EXPECT_EQ(formFactorPointToPolygon(p, n, behind), 0.0);
  EXPECT_NEAR(formFactorPointToPolygon(p, -n, behind), 0.239456, 1e-6);
  // Lying in the tangent plane: edge-on, zero.
  const std::array<Vec3, 3> inPlane{Vec3{1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
  EXPECT_NEAR(formFactorPointToPolygon(p, n, inPlane), 0.0, 1e-15);
  // Coplanar and around p (an element and its own face): zero, not the contour
  // sum's 2π/2π = 1 — also when p is a round-off away from the plane.
  const std::array<Vec3, 4> around{Vec3{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  EXPECT_EQ(formFactorPointToPolygon(p, n, around), 0.0);
  EXPECT_EQ(formFactorPointToPolygon({0.1, 0.2, 1e-17}, n, around), 0.0);
  EXPECT_EQ(formFactorPointToPolygon({0.1, 0.2, -1e-17}, n, around), 0.0);
}

// ---------------------------------------------------------------------------
// Area-to-area factors by integrating the exact point-to-polygon factor

TEST(FormFactorIntegrated, ParallelUnitSquares) {
  // Smooth integrand: 8 panels × order 8 per axis is converged to round-off
  // (measured 1e-15).
  const Rule rule = compositeRule(uniformBreaks(8), 8, 1.0);
  const double f = integratedFormFactor(kFloor, kCeiling, rule, rule) / kFloor.area();
  EXPECT_NEAR(f, 0.1998249, 1e-4);  // the tolerance
  EXPECT_NEAR(f, formFactorParallelRectangles(1, 1, 1), 1e-12);
}

TEST(FormFactorIntegrated, PerpendicularUnitSquaresSharingAnEdge) {
  // The integrand ~ ½ − c·s·log s at the shared edge (s: distance to it) and
  // has weaker corner singularities along it: a geometric mesh (ratio 0.15,
  // smallest panel 0.15^24 ≈ 1e-20) towards the edge, graded at both ends along it.
  const Rule across = compositeRule(gradedBreaks(24, 0.15, false), 10, 1.0);
  const Rule along = compositeRule(gradedBreaks(12, 0.15, true), 10, 1.0);
  // Floor parameterised with u along x (u = 0 is the edge x = 0 it shares with
  // the wall). Measured error 2e-11; a uniform 8 × 8-panel rule only gets ~1e-5.
  const double f = integratedFormFactor(kFloor, kWallX0, across, along) / kFloor.area();
  EXPECT_NEAR(f, 0.2000438, 1e-4);  // the tolerance
  EXPECT_NEAR(f, formFactorPerpendicularRectangles(1, 1, 1), 1e-9);
}

TEST(FormFactorIntegrated, CubeSumRule) {
  // From the floor of the unit cube (inside) to the other five faces.
  const std::array<Rect, 4> walls{
      kWallX0,                                // x = 0, normal +x
      Rect{{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},  // x = 1, normal −x
      Rect{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}},  // y = 0, normal +y
      Rect{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},  // y = 1, normal −y
  };
  // Pointwise, the five faces close the hemisphere: their factors sum to 1.
  Pcg32 rng(5, 9);
  for (int i = 0; i < 100; ++i) {
    const Vec3 p{rng.next(), rng.next(), 0};
    double sum = formFactorPointToPolygon(p, {0, 0, 1}, kCeiling.corners());
    for (const Rect &wall : walls) sum += formFactorPointToPolygon(p, {0, 0, 1}, wall.corners());
    EXPECT_NEAR(sum, 1.0, 1e-13);
  }
  // Integrated: each wall shares an edge with the floor, so grade both axes
  // towards both ends (measured errors ~1e-14).
  const Rule rule = compositeRule(gradedBreaks(24, 0.15, true), 10, 1.0);
  const double opposite = integratedFormFactor(kFloor, kCeiling, rule, rule);
  EXPECT_NEAR(opposite, formFactorParallelRectangles(1, 1, 1), 1e-10);
  double total = opposite;
  for (const Rect &wall : walls) {
    const double adjacent = integratedFormFactor(kFloor, wall, rule, rule);
    EXPECT_NEAR(adjacent, formFactorPerpendicularRectangles(1, 1, 1), 1e-10);
    total += adjacent;
  }
  EXPECT_NEAR(total, 0.1998249 + 4 * 0.2000438, 1e-6);
  EXPECT_NEAR(total, 1.0, 1e-10);
}

TEST(FormFactorIntegrated, Reciprocity) {
  // Small rectangles of different sizes, not touching: smooth integrands, so
  // both sides converge to round-off (measured 4e-15); the issue asks 1e-6.
  auto check = [&](const Rect &i, const Rect &j) {
    const Rule ruleI1 = compositeRule(uniformBreaks(6), 8, length(i.e1));
    const Rule ruleI2 = compositeRule(uniformBreaks(6), 8, length(i.e2));
    const Rule ruleJ1 = compositeRule(uniformBreaks(6), 8, length(j.e1));
    const Rule ruleJ2 = compositeRule(uniformBreaks(6), 8, length(j.e2));
    const double aiFij = integratedFormFactor(i, j, ruleI1, ruleI2);
    const double ajFji = integratedFormFactor(j, i, ruleJ1, ruleJ2);
    EXPECT_GT(aiFij, 0);
    EXPECT_NEAR(aiFij / ajFji, 1.0, 1e-9);
  };
  // Perpendicular: a 0.3 × 0.4 floor piece and a 0.2 × 0.6 wall piece facing it.
  check(Rect{{0, 0.1, 0}, {0.3, 0, 0}, {0, 0.4, 0}}, Rect{{0.6, 0, 0.1}, {0, 0, 0.6}, {0, 0.2, 0}});
  // Parallel, offset: 0.5 × 0.2 facing up, 0.1 × 0.3 facing down 0.4 above.
  check(Rect{{0, 0, 0}, {0.5, 0, 0}, {0, 0.2, 0}}, Rect{{0.3, 0.1, 0.4}, {0, 0.3, 0}, {0.1, 0, 0}});
}

// ---------------------------------------------------------------------------
// Ray-cast (Wallace et al. 1989)

/// A scene of quads, each listed counter-clockwise seen from its front.
Scene sceneOfQuads(const std::vector<std::array<Vec3, 4>> &quads) {
  Scene s;
  s.materials.push_back(Material{});
  s.objects.push_back({"quads", "test"});
  for (const auto &quad : quads) {
    Face f;
    f.vertexCount = 4;
    for (int i = 0; i < 4; ++i) {
      f.vertices[i] = static_cast<uint32_t>(s.positions.size());
      s.positions.push_back(quad[i]);
    }
    s.addFace(f);
  }
  return s;
}

/// The unit square at height `h` centred over the origin, facing down (−z).
std::array<Vec3, 4> squareFacingDown(double h) {
  return {Vec3{-0.5, -0.5, h}, {-0.5, 0.5, h}, {0.5, 0.5, h}, {0.5, -0.5, h}};
}

TEST(FormFactorRayCast, OneSampleIsBounded) {
  // One sample treats the whole source as a coaxial disc of area A: a term is
  // at most A/(π h² + A) (sample right above p), whatever the point — even
  // 0.001 under the source, where 1/(πr²) would explode (the one-sample
  // estimate there is 0.999997).
  for (double h : {1.0, 0.1, 0.001}) {
    const auto source = squareFacingDown(h);
    Scene scene = sceneOfQuads({source});
    RayTracer tracer(scene);
    const double bound = 1 / (kPi * h * h + 1);
    for (uint64_t seed = 0; seed < 200; ++seed) {
      Pcg32 rng(seed, 1);
      const double f = formFactorRayCast(tracer, {0, 0, 0}, {0, 0, 1}, source, {0, 0, -1}, 1, rng);
      EXPECT_GT(f, 0);
      EXPECT_LE(f, bound + 1e-15);
    }
  }
  EXPECT_NEAR(1 / (kPi * 1e-6 + 1), 0.999997, 1e-6);
}

TEST(FormFactorRayCast, StratifiedEstimateConvergesUnderUnitSquare) {
  const auto source = squareFacingDown(1);
  Scene scene = sceneOfQuads({source});
  RayTracer tracer(scene);
  const double exact = formFactorPointToPolygon({0, 0, 0}, {0, 0, 1}, source);
  // RMS error over 100 independent generators per n: it must fall with n.
  double previous = INFINITY;
  for (int n : {1, 4, 16, 64, 256}) {
    double sumSquares = 0, worst = 0;
    for (uint64_t seed = 0; seed < 100; ++seed) {
      Pcg32 rng(seed, 17);
      const double error = formFactorRayCast(tracer, {0, 0, 0}, {0, 0, 1}, source, {0, 0, -1}, n, rng) - exact;
      sumSquares += error * error;
      worst = std::max(worst, std::abs(error));
    }
    const double rms = std::sqrt(sumSquares / 100);
    std::printf("[ ray-cast ] n = %3d  rms error %.2e  worst %.2e\n", n, rms, worst);
    EXPECT_LT(rms, previous);
    previous = rms;
    if (n == 256) {
      EXPECT_LT(worst, 2e-3);
    }
  }
}

TEST(FormFactorRayCast, TriangleAndGeneralQuadSourcesMatchExact) {
  // Non-parallelogram sources take the triangle path (Heitz map, area-
  // proportional split). Their stratified error falls as 1/n like the square's;
  // at n = 1024 the relative error over 400 generators had rms 4e-4 (triangle)
  // and 7e-4 (trapezoid), worst 1.2e-3 and 2.1e-3, the disc bias ~ −2e-4.
  const std::array<Vec3, 3> triangle{Vec3{-0.6, -0.4, 1}, {0.1, 0.7, 1.2}, {0.7, -0.5, 0.9}};
  const std::array<Vec3, 4> trapezoid{Vec3{-0.8, -0.4, 1}, {-0.3, 0.5, 1}, {0.3, 0.5, 1}, {0.8, -0.4, 1}};
  Scene scene;  // nothing to occlude
  RayTracer tracer(scene);
  auto check = [&](std::span<const Vec3> source) {
    Vec3 normal = normalize(cross(source[1] - source[0], source[2] - source[0]));
    ASSERT_LT(normal.z, 0);  // facing the point below
    const double exact = formFactorPointToPolygon({0, 0, 0}, {0, 0, 1}, source);
    Pcg32 rng(3, 4);
    double visibleFraction = -1;
    const double f = formFactorRayCast(tracer, {0, 0, 0}, {0, 0, 1}, source, normal, 1024, rng, visibleFraction);
    EXPECT_NEAR(f / exact, 1.0, 4e-3);
    EXPECT_EQ(visibleFraction, 1.0);
  };
  check(triangle);
  check(trapezoid);
}

TEST(FormFactorRayCast, OneSidedAndDeterministic) {
  const auto source = squareFacingDown(1);
  Scene scene = sceneOfQuads({source});
  RayTracer tracer(scene);
  Pcg32 rng(1, 2);
  // The source's back side, and a source behind the receiver, give nothing.
  double visibleFraction = -1;
  EXPECT_EQ(formFactorRayCast(tracer, {0, 0, 0}, {0, 0, 1}, source, {0, 0, 1}, 16, rng, visibleFraction), 0.0);
  EXPECT_EQ(visibleFraction, 0.0);
  EXPECT_EQ(formFactorRayCast(tracer, {0, 0, 2}, {0, 0, 1}, source, {0, 0, -1}, 16, rng), 0.0);
  // The same generator state gives the same estimate.
  Pcg32 a(42, 7), b(42, 7);
  EXPECT_EQ(formFactorRayCast(tracer, {0.1, 0, 0}, {0, 0, 1}, source, {0, 0, -1}, 64, a),
            formFactorRayCast(tracer, {0.1, 0, 0}, {0, 0, 1}, source, {0, 0, -1}, 64, b));
}

TEST(FormFactorRayCast, OccluderCoveringHalfTheSourceHalvesTheEstimate) {
  const auto source = squareFacingDown(1);
  // Halfway up, covering x > 0 as seen from the origin (and beyond the source's shadow).
  const std::array<Vec3, 4> occluder{Vec3{0, -1, 0.5}, {1, -1, 0.5}, {1, 1, 0.5}, {0, 1, 0.5}};
  Scene open = sceneOfQuads({source}), shaded = sceneOfQuads({source, occluder});
  RayTracer openTracer(open), shadedTracer(shaded);
  const double exact = formFactorPointToPolygon({0, 0, 0}, {0, 0, 1}, source);
  for (uint64_t seed = 0; seed < 20; ++seed) {
    // Same generator state: the same sample points, only visibility differs.
    Pcg32 a(seed, 3), b(seed, 3);
    double openFraction, shadedFraction;
    const double full = formFactorRayCast(openTracer, {0, 0, 0}, {0, 0, 1}, source, {0, 0, -1}, 256, a, openFraction);
    const double half =
        formFactorRayCast(shadedTracer, {0, 0, 0}, {0, 0, 1}, source, {0, 0, -1}, 256, b, shadedFraction);
    EXPECT_EQ(openFraction, 1.0);
    // The 16 × 16 grid splits at x = 0: exactly half the samples are hidden.
    EXPECT_EQ(shadedFraction, 0.5);
    // By symmetry the two halves carry equal shares; stratification keeps the
    // imbalance within the n = 256 error bound (measured worst 6e-4 and 1.5e-3).
    EXPECT_NEAR(half, 0.5 * exact, 2e-3);
    EXPECT_NEAR(half / full, 0.5, 5e-3);
  }
}

// ---------------------------------------------------------------------------
// Hemicube

TEST(Hemicube, DeltaFormFactorTotalsMatchReferenceTable) {
  struct Row {
    int resolution;
    double top, side, total;
  };
  const Row table[] = {{8, 0.556401, 0.113042, 1.008569},
                       {16, 0.554696, 0.111857, 1.002123},
                       {32, 0.554269, 0.111565, 1.000530},
                       {64, 0.554162, 0.111493, 1.000132}};
  for (const Row &row : table) {
    Hemicube cube(row.resolution);
    EXPECT_EQ(cube.resolution(), row.resolution);
    EXPECT_NEAR(cube.topFaceDeltaFormFactor(), row.top, 1e-6) << row.resolution;
    EXPECT_NEAR(cube.sideFaceDeltaFormFactor(), row.side, 1e-6) << row.resolution;
    EXPECT_NEAR(cube.totalDeltaFormFactor(), row.total, 1e-6) << row.resolution;
  }
  EXPECT_EQ(Hemicube(7).resolution(), 8);  // rounded up to even
}

/// The inside of the unit cube; face k is (−x, +x, −y, +y, −z, +z), as in test::closedBox.
Scene unitBox() {
  const int walls[6] = {0, 0, 0, 0, 0, 0};
  Scene scene = test::closedBox(1.0, walls);
  scene.materials.push_back(Material{});
  return scene;
}

/// Exact F from the floor's centre to the ceiling and to each wall.
std::array<double, 6> exactFromFloorCentre(const Scene &scene, const Vec3 &p) {
  std::array<double, 6> exact{};
  for (size_t k = 0; k < 6; ++k) {
    const Face &face = scene.faces[k];
    std::array<Vec3, 4> polygon;
    for (int i = 0; i < 4; ++i) polygon[i] = scene.positions[face.vertices[i]];
    exact[k] = formFactorPointToPolygon(p, {0, 0, 1}, polygon);
  }
  return exact;
}

TEST(Hemicube, GatherInClosedBoxMatchesExactFactors) {
  Scene scene = unitBox();
  RayTracer tracer(scene);
  const Vec3 p{0.5, 0.5, 0};
  const auto exact = exactFromFloorCentre(scene, p);
  EXPECT_NEAR(exact[5], 0.239456, 1e-6);
  EXPECT_EQ(exact[4], 0.0);
  // Per-face error: the table's midpoint error (the ceiling's outline falls on
  // pixel edges when aligned: 1.8e-4 at res 32, falling as 1/res²) plus the
  // pixels straddling outlines, which go wholly to one face: O(1/res). Aligned,
  // the seams between walls run along the top face's diagonals through pixel
  // centres, where Embree picks either wall (measured 0.078/res, bound 0.1/res).
  // Rotated, an outline can run along a row of pixel centres, a half-pixel
  // strip misassigned: worst over 500 angles 0.29/res, bound 0.4/res (res 128:
  // 3.1e-3; rms over angles is only 1.2e-4). Measured errors are printed.
  const struct {
    int resolution;
    double aligned, rotated;
  } cases[] = {{32, 0.1 / 32, 0.4 / 32}, {64, 0.1 / 64, 0.4 / 64}, {128, 0.1 / 128, 0.4 / 128}};
  for (const auto &c : cases) {
    Hemicube cube(c.resolution);
    for (bool rotate : {false, true}) {
      Pcg32 rng(9, 1);
      std::vector<double> factors(6, 0.0);
      const double escaped = cube.gather(
          tracer, p, {0, 0, 1}, [](const Hit &hit) { return static_cast<int>(hit.face); }, factors, rng, rotate);
      EXPECT_EQ(escaped, 0.0);  // closed: nothing escapes
      double sum = 0, worst = 0;
      for (int k = 0; k < 6; ++k) {
        sum += factors[k];
        worst = std::max(worst, std::abs(factors[k] - exact[k]));
        EXPECT_NEAR(factors[k], exact[k], rotate ? c.rotated : c.aligned) << "res " << c.resolution << " face " << k;
      }
      EXPECT_EQ(factors[4], 0.0);  // the floor it stands on
      // Every pixel hit something: the gathered sum is the table's total.
      EXPECT_NEAR(sum, cube.totalDeltaFormFactor(), 1e-12);
      std::printf("[ hemicube ] res %3d %-9s worst face error %.2e (ceiling %.2e)\n", c.resolution,
                  rotate ? "rotated" : "aligned", worst, std::abs(factors[5] - exact[5]));
    }
  }
}

TEST(Hemicube, RandomRotationKeepsTheSum) {
  Scene scene = unitBox();
  RayTracer tracer(scene);
  Hemicube cube(32);
  Pcg32 rng(77, 5);
  for (int trial = 0; trial < 10; ++trial) {
    // Off-centre and tilted, so the outlines cross pixels differently each time.
    const Vec3 p{0.2 + 0.6 * rng.next(), 0.2 + 0.6 * rng.next(), 0.3 + 0.4 * rng.next()};
    const Vec3 n = normalize(Vec3{rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5});
    std::vector<double> factors(6, 0.0);
    EXPECT_EQ(cube.gather(
                  tracer, p, n, [](const Hit &hit) { return static_cast<int>(hit.face); }, factors, rng),
              0.0);
    double sum = 0;
    for (double f : factors) sum += f;
    EXPECT_NEAR(sum, cube.totalDeltaFormFactor(), 1e-12);
  }
}

TEST(Hemicube, OpenSceneReturnsWhatEscapes) {
  const auto source = squareFacingDown(1);
  Scene scene = sceneOfQuads({source});
  RayTracer tracer(scene);
  Hemicube cube(64);
  Pcg32 rng(1, 1);
  std::vector<double> factors(1, 0.0);
  const double escaped = cube.gather(
      tracer, {0, 0, 0}, {0, 0, 1}, [](const Hit &) { return 0; }, factors, rng, false);
  // Aligned, the square's outline falls on pixel edges (x, y = ±0.5 on the top
  // face): only the midpoint error remains, like the table's top row.
  EXPECT_NEAR(factors[0], 0.239456, 1e-4);  // measured 4.5e-5
  EXPECT_NEAR(factors[0] + escaped, cube.totalDeltaFormFactor(), 1e-12);
  // A target of −1 is ignored, and is not counted as escaping.
  std::vector<double> none(1, 0.0);
  const double escapedAgain = cube.gather(
      tracer, {0, 0, 0}, {0, 0, 1}, [](const Hit &) { return -1; }, none, rng, false);
  EXPECT_EQ(none[0], 0.0);
  EXPECT_NEAR(escapedAgain, escaped, 1e-15);
}

TEST(FastAngle, AgreesWithAtan2ToDoublePrecision) {
  // The contour integral's angles: atan2(|a × b|, a·b), y ≥ 0, over the whole
  // half-plane and many decades of size, to a few ulps.
  Pcg32 rng(17, 3);
  double worst = 0;
  for (int k = 0; k < 200000; ++k) {
    const double scale = std::pow(10.0, 12 * rng.next() - 6);
    const double y = scale * rng.next(), x = scale * (2 * rng.next() - 1);
    const double exact = std::atan2(y, x);
    worst = std::max(worst, std::abs(angleFromSineAndCosine(y, x) - exact) / std::max(exact, 1e-300));
  }
  EXPECT_LT(worst, 1e-15);
  for (double t : {0.0, 1e-300, 1e-8, 0.66, 0.6600001, 1.0, 2.414213562373095, 2.4142136, 1e8, 1e300})
    EXPECT_NEAR(atanNonNegative(t), std::atan(t), 4e-16 * std::max(1.0, std::atan(t))) << t;
  EXPECT_EQ(angleFromSineAndCosine(0.0, 0.0), 0.0);
  EXPECT_NEAR(angleFromSineAndCosine(1.0, 0.0), kPi / 2, 1e-16);
  EXPECT_NEAR(angleFromSineAndCosine(0.0, -1.0), kPi, 1e-15);
}

}  // namespace
}  // namespace radiant
