// Point-to-area form factors: exact (Lambert's contour integral) and ray-cast
// (Wallace, Elmquist & Haines 1989).
//
// formFactorPointToPolygon — Lambert's contour integral (Baum, Rushmeier &
//   Winget 1989; Cohen & Wallace ch. 4):
//     F(dA → A) = (1/2π) |Σ_k β_k n·(R_k × R_{k+1}) / |R_k × R_{k+1}||,
//   β_k the angle between R_k = v_k − p and R_{k+1}. Exact and unoccluded; the
//   reference the other estimators and the tests are measured against.
//
// formFactorRayCast — Wallace, Elmquist & Haines, SIGGRAPH 1989:
//     F(dA → A) ≈ Σ_k δ_k cosθ_p cosθ_s a / (π r_k² + a),   a = A / n,
//   each of n equal-area pieces of the source treated as a coaxial disc, so a
//   term stays below 1 however close the point is. Includes visibility (one
//   shadow ray per sample); the estimator progressive shooting to vertices uses.
#include "radiosity/form_factor.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "util/fast_angle.h"
#include "util/sampling.h"

namespace radiant {

namespace {

/// Splits a source polygon into pieces of exactly equal area for stratified
/// sampling. The unit square maps onto the polygon with constant Jacobian
/// (area-preserving up to the factor A), so a grid of equal cells in the
/// square gives equal-area pieces of the source:
///   - a parallelogram: the bilinear (here affine) map of the square;
///   - a triangle: Heitz 2019's low-distortion map (sampleUniformTriangle);
///   - any other quad: two triangles, u1 first choosing the triangle in
///     proportion to its area and then rescaled, so each triangle receives its
///     share of the strata.
struct SourceSampler {
  Vec3 v[4];
  int vertexCount = 0;
  bool parallelogram = false;
  double area = 0;
  double firstTriangleShare = 1;  ///< area of (v0, v1, v2) over the total

  explicit SourceSampler(std::span<const Vec3> source) {
    vertexCount = static_cast<int>(std::min<size_t>(source.size(), 4));
    for (int i = 0; i < vertexCount; ++i) v[i] = source[i];
    const double a1 = 0.5 * length(cross(v[1] - v[0], v[2] - v[0]));
    if (vertexCount == 3) {
      area = a1;
      return;
    }
    const double a2 = 0.5 * length(cross(v[2] - v[0], v[3] - v[0]));
    area = a1 + a2;
    firstTriangleShare = area > 0 ? a1 / area : 1;
    // v0 + v2 = v1 + v3 for a parallelogram; compare against the quad's size.
    const Vec3 gap = (v[0] + v[2]) - (v[1] + v[3]);
    const double scale = std::max(length(v[1] - v[0]), length(v[3] - v[0]));
    parallelogram = length(gap) <= 1e-6 * scale;  // the bilinear map is then area-preserving to 1e-6
  }

  /// Lengths of the two edges the grid's axes follow (u1, u2).
  double axisLength(int axis) const {
    if (vertexCount == 4 && parallelogram) return length(axis == 0 ? v[1] - v[0] : v[3] - v[0]);
    return 1;  // triangles: the Heitz map has no preferred long axis
  }

  Vec3 point(double u1, double u2) const {
    if (vertexCount == 4 && parallelogram) return v[0] + (v[1] - v[0]) * u1 + (v[3] - v[0]) * u2;
    const Vec3 *t0 = &v[0], *t1 = &v[1], *t2 = &v[2];
    if (vertexCount == 4) {
      if (u1 < firstTriangleShare) {
        u1 /= firstTriangleShare;
      } else {
        u1 = (u1 - firstTriangleShare) / (1 - firstTriangleShare);
        t1 = &v[2];
        t2 = &v[3];
      }
      u1 = std::min(u1, 1.0);
    }
    double b1, b2;
    sampleUniformTriangle(u1, u2, b1, b2);
    return *t0 * (1 - b1 - b2) + *t1 * b1 + *t2 * b2;
  }
};

/// n1 × n2 = samples with n1 the largest divisor ≤ √samples (a square grid
/// when samples is a square; strips only when it is prime).
void gridDimensions(int samples, int &small, int &large) {
  small = static_cast<int>(std::sqrt(static_cast<double>(samples)));
  while (small > 1 && samples % small != 0) --small;
  large = samples / small;
}

}  // namespace

/// Sutherland–Hodgman clip of `polygon` to the open half-space dot(x − p, n) > 0.
/// The part behind the receiver's tangent plane is invisible to it, and the
/// contour formula is only valid for a polygon entirely in front (C&W ch. 4).
///
/// The part *in* the plane is dropped too: a polygon coplanar with the receiver
/// (its own face, a neighbouring element of the same wall) exchanges nothing,
/// yet the contour sum of a polygon lying in the plane around p is ±2π, F = 1.
/// Signed distances within a round-off tolerance of the polygon's size count
/// as in the plane, so a receiver point a few ulps off its floor still sees 0.
/// A vertex exactly in the plane next to one in front is kept (as the
/// crossing with t = 0 or 1), so a wall sharing an edge with the receiver's
/// face is not shortened.
void clipToFrontHalfSpace(const Vec3 &p, const Vec3 &n, std::span<const Vec3> polygon, std::vector<Vec3> &out) {
  out.clear();
  const size_t count = polygon.size();
  double size = 0;
  for (const Vec3 &v : polygon) size = std::max(size, length(v - p));
  const double tolerance = 1e-12 * size;
  auto signedDistance = [&](const Vec3 &v) {
    const double d = dot(v - p, n);
    return std::abs(d) <= tolerance ? 0.0 : d;
  };
  for (size_t k = 0; k < count; ++k) {
    const Vec3 &a = polygon[k];
    const Vec3 &b = polygon[(k + 1) % count];
    const double da = signedDistance(a), db = signedDistance(b);
    if (da > 0) out.push_back(a);
    // The edge enters or leaves the half-space: add the crossing point.
    if ((da > 0) != (db > 0)) {
      const double t = da / (da - db);  // da ≠ db here; t ∈ [0, 1]
      out.push_back(a + (b - a) * t);
    }
  }
}

double formFactorPointToPolygon(const Vec3 &p, const Vec3 &n, std::span<const Vec3> polygon) {
  if (polygon.size() < 3) return 0;
  // Wholly in front of p's plane (the usual case): no clipping, no copy.
  // The test is clipToFrontHalfSpace's, with its tolerance.
  double size2 = 0;
  bool inFront = true;
  for (const Vec3 &v : polygon) size2 = std::max(size2, dot(v - p, v - p));
  const double tolerance = 1e-12 * std::sqrt(size2);
  for (const Vec3 &v : polygon) inFront = inFront && dot(v - p, n) > tolerance;
  std::span<const Vec3> integrated = polygon;
  thread_local std::vector<Vec3> clipped;
  if (!inFront) {
    clipToFrontHalfSpace(p, n, polygon, clipped);
    if (clipped.size() < 3) return 0;
    integrated = clipped;
  }

  double sum = 0;
  for (size_t k = 0; k < integrated.size(); ++k) {
    const Vec3 r0 = integrated[k] - p;
    const Vec3 r1 = integrated[(k + 1) % integrated.size()] - p;
    const Vec3 c = cross(r0, r1);
    const double cn = length(c);
    // An edge collinear with p (or a repeated vertex) spans no solid angle.
    if (!(cn > 0)) continue;
    // The angle from its sine and cosine, not acos: acos loses half its
    // digits at small angles.
    sum += angleFromSineAndCosine(cn, dot(r0, r1)) * dot(n, c) / cn;
  }
  // For a planar polygon wholly in front of p every term has the sign set by
  // the winding as seen from p (positive when the polygon turns clockwise as
  // seen from p), so the magnitude of the sum is the winding-independent
  // answer: the signed sum taken with the orientation that makes it positive.
  return std::abs(sum) / (2 * kPi);
}

double visibleFormFactor(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, const Vec3 &rayNormal,
                         std::span<const Vec3> polygon, const Vec3 &polygonNormal, const VisibilitySamples &samples) {
  thread_local std::vector<Vec3> front;
  clipToFrontHalfSpace(p, n, polygon, front);
  if (front.size() < 3) return 0;
  const double f = formFactorPointToPolygon(p, n, front);
  if (f <= 0) return 0;
  if (samples.centroid) return tracer.visible(p, rayNormal, polygonCentroid(front), polygonNormal) ? f : 0.0;
  const int grid = samples.grid;
  int visible = 0;
  for (int a = 0; a < grid; ++a)
    for (int b = 0; b < grid; ++b)
      visible += tracer.visible(
          p, rayNormal, sampleConvexPolygon(front, (a + samples.u1) / grid, (b + samples.u2) / grid), polygonNormal);
  return f * visible / double(grid * grid);
}

double polygonWarp(std::span<const Vec3> polygon, const Vec3 &n) {
  double warp = 0;
  for (size_t k = 1; k < polygon.size(); ++k) warp = std::max(warp, std::abs(dot(polygon[k] - polygon[0], n)));
  return warp;
}

Vec3 vectorFormFactor(const Vec3 &p, std::span<const Vec3> polygon) {
  Vec3 sum, centroid;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Vec3 r0 = polygon[k] - p, r1 = polygon[(k + 1) % polygon.size()] - p;
    const Vec3 c = cross(r0, r1);
    const double cn = length(c);
    centroid += polygon[k];
    if (!(cn > 0)) continue;
    sum += c * (angleFromSineAndCosine(cn, dot(r0, r1)) / cn);
  }
  sum = sum / (2 * kPi);
  // The sign follows the winding as seen from p: turn it towards the polygon.
  if (dot(sum, centroid / double(polygon.size()) - p) < 0) sum = -sum;
  return sum;
}

double formFactorRayCast(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, std::span<const Vec3> source,
                         const Vec3 &sourceNormal, int samples, Pcg32 &rng, double &visibleFraction) {
  visibleFraction = 0;
  if (source.size() < 3) return 0;
  samples = std::max(samples, 1);
  const SourceSampler sampler(source);
  if (!(sampler.area > 0)) return 0;

  int small, large;
  gridDimensions(samples, small, large);
  // Put the finer subdivision along the longer edge, so cells stay compact.
  int count1 = large, count2 = small;
  if (sampler.axisLength(0) < sampler.axisLength(1)) std::swap(count1, count2);

  const double pieceArea = sampler.area / samples;  // a = A/n
  double sum = 0;
  int tested = 0, visible = 0;
  for (int i = 0; i < count1; ++i)
    for (int j = 0; j < count2; ++j) {
      // Draw both numbers before any early exit: the sample points then
      // depend only on rng, not on geometry or visibility.
      const double u1 = (i + rng.next()) / count1;
      const double u2 = (j + rng.next()) / count2;
      const Vec3 y = sampler.point(u1, u2);
      const Vec3 toSource = y - p;
      const double r2 = dot(toSource, toSource);
      if (!(r2 > 0)) continue;
      const double r = std::sqrt(r2);
      const double cosReceiver = dot(n, toSource) / r;
      const double cosSource = -dot(sourceNormal, toSource) / r;  // dot(p − y, sourceNormal)/r
      // One-sided: behind the receiver, or the source's back side, gives nothing.
      if (cosReceiver <= 0 || cosSource <= 0) continue;
      ++tested;
      if (!tracer.visible(p, n, y, sourceNormal)) continue;
      ++visible;
      sum += pieceArea * cosReceiver * cosSource / (kPi * r2 + pieceArea);
    }
  // Visibility among the samples that face both ways: 1 means nothing in the
  // scene occludes any of them (HSA records this per link); 0 when none face.
  visibleFraction = tested > 0 ? static_cast<double>(visible) / tested : 0.0;
  return sum;
}

double formFactorRayCast(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, std::span<const Vec3> source,
                         const Vec3 &sourceNormal, int samples, Pcg32 &rng) {
  double visibleFraction;
  return formFactorRayCast(tracer, p, n, source, sourceNormal, samples, rng, visibleFraction);
}

}  // namespace radiant
