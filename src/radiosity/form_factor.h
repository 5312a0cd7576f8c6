// Form factors: the geometric coupling of radiosity (Cohen & Wallace ch. 4).
//
// F(dA → A): the fraction of the energy leaving a differential area at a
// point p (normal n, Lambertian) that arrives at polygon A. All estimators here
// are of that point-to-area kind; element-to-element factors are built from
// them by the solvers (centre point, or averaged over sample points).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "raytrace/ray_tracer.h"
#include "util/math.h"
#include "util/random.h"

namespace radiant {

/// Sutherland–Hodgman clip of `polygon` to the open half-space in front of
/// p's tangent plane, dot(x − p, n) > 0: the part of a source a receiver at p
/// can see at all. A polygon in that plane (within round-off of its size)
/// clips to nothing; `out` may then hold fewer than 3 vertices.
void clipToFrontHalfSpace(const Vec3 &p, const Vec3 &n, std::span<const Vec3> polygon, std::vector<Vec3> &out);

/// Unoccluded F(dA → polygon) by Lambert's contour integral (C&W ch. 4),
/// with the polygon first clipped to the half-space in front of p's tangent
/// plane (the part behind the receiver contributes nothing; a polygon lying in
/// that plane gives 0). Exact for planar polygons of any size and distance;
/// independent of the polygon's winding; `polygon` has 3 or more vertices.
double formFactorPointToPolygon(const Vec3 &p, const Vec3 &n, std::span<const Vec3> polygon);

/// Where visibleFormFactor aims its shadow rays on the part of the polygon in
/// front of the receiver's tangent plane.
struct VisibilitySamples {
  bool centroid = false;  ///< one ray, to the front part's centroid (the same point for every receiver point)
  /// Otherwise grid × grid rays, to sampleConvexPolygon(front, (a + u1)/grid, (b + u2)/grid):
  /// the cells' centres at u = ½, or one uniformly random point with grid 1 and random u.
  int grid = 1;
  double u1 = 0.5, u2 = 0.5;
};

/// F(dA → polygon) × V, the point-to-polygon factor with visibility (C&W
/// eq. 4.9's kernel integrated over the polygon, V estimated by shadow rays):
/// the exact factor of the part of the polygon in front of p's tangent
/// plane (normal n), times the fraction of the shadow rays from p (offset
/// along rayNormal, the geometric normal at p) to points of that part that
/// reach it (polygonNormal: its front). Visibility is sampled on the part in
/// front only: a point behind the plane would always read as occluded, by
/// p's own surface. The per-pixel gathers (reichert) and kok's removal of
/// its sources from the solution use it; the solvers keep their own
/// estimators, whose sampling is part of their published results.
double visibleFormFactor(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, const Vec3 &rayNormal,
                         std::span<const Vec3> polygon, const Vec3 &polygonNormal, const VisibilitySamples &samples);

/// How far a polygon's vertices stray from the plane through its first vertex
/// with normal n: 0 for a triangle, about 10⁻⁸ of its size for a quad read
/// from a file in single precision (tinyobjloader's floats). A point closer
/// than this to that plane lies on the polygon's surface as far as the tests
/// "in front of the source" and "in the occluder's plane" can tell; taken as
/// in front, a point on an emitting quad saw its own quad as a whole
/// hemisphere of light (F = 1) and a furnace sphere of OBJ quads came out
/// 40 % too bright.
double polygonWarp(std::span<const Vec3> polygon, const Vec3 &n);

/// The vector form factor of a polygon at p (Lambert; Arvo 1994's vector
/// irradiance per unit radiosity): Γ = (1/2π) Σ_k β_k û_k, û_k the unit
/// normal of the plane through p and edge k, oriented towards the polygon.
/// For every unit normal n that has the whole polygon in front of it,
/// F(dA(p, n) → polygon) = n·Γ: the form factor is linear in the receiver's
/// normal. A cluster of small surfaces near a polygon takes its light per
/// surface from this one vector.
Vec3 vectorFormFactor(const Vec3 &p, std::span<const Vec3> polygon);

/// Ray-cast F(dA → source) after Wallace, Elmquist & Haines, SIGGRAPH 1989:
/// the source polygon (planar, 3 or 4 vertices, front normal
/// `sourceNormal`) is split into `samples` pieces of equal area (stratified),
/// each treated as a coaxial disc a = A/n: Σ δ_k cosθ_p cosθ_s a / (π r² + a),
/// with visibility δ_k from a shadow ray. Only the source's front side
/// contributes (one-sided, as shooting is). Deterministic for a given `rng`.
double formFactorRayCast(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, std::span<const Vec3> source,
                         const Vec3 &sourceNormal, int samples, Pcg32 &rng);

/// Like formFactorRayCast, but also returns the fraction of its samples that
/// were visible (0: none, 1: all), which hierarchical radiosity records per link.
double formFactorRayCast(const RayTracer &tracer, const Vec3 &p, const Vec3 &n, std::span<const Vec3> source,
                         const Vec3 &sourceNormal, int samples, Pcg32 &rng, double &visibleFraction);

}  // namespace radiant
