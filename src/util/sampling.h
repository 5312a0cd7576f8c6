// Sampling routines with their densities. Each one is checked by a chi-square
// goodness-of-fit test in tests/sampling_test.cpp.
#pragma once

#include <algorithm>
#include <span>

#include "util/math.h"

namespace radiant {

/// Cosine-weighted direction about +z (Malley's method: a uniform disc point
/// lifted to the hemisphere, Shirley–Chiu concentric mapping for low distortion).
inline Vec3 sampleCosineHemisphere(double u1, double u2) {
  double a = 2 * u1 - 1, b = 2 * u2 - 1;
  double r = 0, phi = 0;
  if (a != 0 || b != 0) {
    if (a * a > b * b) {
      r = a;
      phi = (kPi / 4) * (b / a);
    } else {
      r = b;
      phi = (kPi / 2) - (kPi / 4) * (a / b);
    }
  }
  double x = r * std::cos(phi), y = r * std::sin(phi);
  return {x, y, std::sqrt(std::max(0.0, 1 - x * x - y * y))};
}
/// Density per unit solid angle of sampleCosineHemisphere.
inline double cosineHemispherePdf(double cosTheta) {
  return cosTheta > 0 ? cosTheta * kInvPi : 0.0;
}

/// Veach's power heuristic (β = 2): the weight of a sample drawn with density
/// pdfA when another strategy would have drawn it with density pdfB.
inline double powerHeuristic(double pdfA, double pdfB) {
  double a = pdfA * pdfA, b = pdfB * pdfB;
  return a + b > 0 ? a / (a + b) : 0.0;
}

/// Uniform point on a triangle as barycentrics (b1, b2) (Heitz 2019,
/// "A low-distortion map between triangle and square").
inline void sampleUniformTriangle(double u1, double u2, double &b1, double &b2) {
  if (u2 > u1) {
    b1 = u1 / 2;
    b2 = u2 - b1;
  } else {
    b2 = u2 / 2;
    b1 = u1 - b2;
  }
}

/// GGX (Trowbridge–Reitz) normal distribution D(h) for roughness α, h in the local frame.
inline double ggxD(const Vec3 &h, double alpha) {
  if (h.z <= 0) return 0;
  double a2 = alpha * alpha;
  double c2 = h.z * h.z;
  double d = c2 * (a2 - 1) + 1;
  return a2 / (kPi * d * d);
}
/// Samples a microfacet normal with density D(h)·cosθh (Walter et al. 2007, eq. 35–36).
inline Vec3 sampleGgxNormal(double u1, double u2, double alpha) {
  double tan2 = alpha * alpha * u1 / std::max(1e-300, 1 - u1);
  double cosTheta = 1 / std::sqrt(1 + tan2);
  double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  double phi = 2 * kPi * u2;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
/// Smith's masking term G1 for GGX (Walter et al. 2007, eq. 34).
inline double ggxG1(const Vec3 &v, double alpha) {
  double c = std::abs(v.z);
  if (c >= 1) return 1;
  double tan2 = (1 - c * c) / (c * c);
  return 2 / (1 + std::sqrt(1 + alpha * alpha * tan2));
}

}  // namespace radiant

namespace radiant {

/// Uniform point on a planar triangle or quad (`count` 3 or 4 vertices): a
/// quad is split into (v0, v1, v2) and (v0, v2, v3), u1 choosing between them
/// in proportion to their areas and then rescaled.
inline Vec3 samplePlanarPolygon(const Vec3 *v, int count, double u1, double u2) {
  const Vec3 *a = &v[0], *b = &v[1], *c = &v[2];
  if (count == 4) {
    double first = length(cross(v[1] - v[0], v[2] - v[0]));
    double second = length(cross(v[2] - v[0], v[3] - v[0]));
    double split = first + second > 0 ? first / (first + second) : 1;
    if (u1 < split) {
      u1 /= split;
    } else {
      u1 = std::min(1.0, (u1 - split) / (1 - split));
      b = &v[2], c = &v[3];
    }
  }
  double b1, b2;
  sampleUniformTriangle(u1, u2, b1, b2);
  return *a * (1 - b1 - b2) + *b * b1 + *c * b2;
}

/// Uniform point on a convex planar polygon of any vertex count (a clipped
/// element): a fan of triangles from vertex 0, u1 choosing one in proportion
/// to its area and then rescaled.
inline Vec3 sampleConvexPolygon(std::span<const Vec3> v, double u1, double u2) {
  double total = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) total += length(cross(v[k] - v[0], v[k + 1] - v[0]));
  size_t chosen = 1;
  double target = u1 * total, running = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) {
    double a = length(cross(v[k] - v[0], v[k + 1] - v[0]));
    chosen = k;
    if (running + a > target || k + 2 == v.size()) {
      u1 = a > 0 ? std::clamp((target - running) / a, 0.0, 1.0) : 0.0;
      break;
    }
    running += a;
  }
  double b1, b2;
  sampleUniformTriangle(u1, u2, b1, b2);
  return v[0] * (1 - b1 - b2) + v[chosen] * b1 + v[chosen + 1] * b2;
}

/// Area centroid of a convex planar polygon.
inline Vec3 polygonCentroid(std::span<const Vec3> v) {
  Vec3 sum{};
  double total = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) {
    double a = length(cross(v[k] - v[0], v[k + 1] - v[0]));
    sum += (v[0] + v[k] + v[k + 1]) * (a / 3);
    total += a;
  }
  return total > 0 ? sum / total : v[0];
}

}  // namespace radiant
