// Visibility for every stage: closest hit and occlusion over the scene's
// triangles, through one Embree 3 BVH.
//
// Embree works in single precision on its own copy of the vertices; hit
// positions and normals are recomputed here in double from the scene's data,
// so callers get the accuracy the radiosity stages need.
#pragma once

#include <embree3/rtcore.h>

#include <span>
#include <vector>

#include "scene/scene.h"

namespace radiant {

struct Hit {
  double distance = 0;    ///< along the (unit) ray direction, metres
  uint32_t triangle = 0;  ///< index into Scene::triangles
  double b1 = 0, b2 = 0;  ///< barycentrics of vertices 1 and 2 (vertex 0 has 1 − b1 − b2)
  Vec3 position;
  Vec3 geometricNormal;  ///< unit, the triangle's front side (counter-clockwise winding)
  Vec3 shadingNormal;    ///< unit, interpolated vertex normals, oriented to the geometric normal's side
  uint32_t material = 0;
  uint32_t face = 0;
};

/// What a stream query returns per ray: 16 bytes, enough to complete a Hit
/// later (RayTracer::completeHit) for the rays a caller actually needs.
struct HitRecord {
  static constexpr uint32_t kNone = 0xFFFFFFFFu;
  uint32_t triangle = kNone;  ///< kNone: the ray hit nothing
  float distance = 0;         ///< Embree's t along the ray
  float b1 = 0, b2 = 0;       ///< barycentrics of vertices 1 and 2
  bool found() const { return triangle != kNone; }
};

class RayTracer {
 public:
  explicit RayTracer(const Scene &scene);
  ~RayTracer();
  RayTracer(const RayTracer &) = delete;
  RayTracer &operator=(const RayTracer &) = delete;

  /// Closest hit with distance in (tMin, tMax); false if none.
  bool intersect(const Ray &ray, Hit &hit, double tMax = INFINITY) const;
  /// The closest hit's face, triangle and position only: no shading normal
  /// (vertex normals are three more scattered reads per hit). For the
  /// solvers that cast tens of millions of rays to find where light lands.
  bool intersectPosition(const Ray &ray, Hit &hit) const;
  /// True if anything blocks the open segment (tMin, tMax) of the ray.
  bool occluded(const Ray &ray, double tMax) const;
  /// True if the two points see each other (both offset off their surfaces).
  bool visible(const Vec3 &from, const Vec3 &fromNormal, const Vec3 &to, const Vec3 &toNormal) const;
  /// True when nothing lies between a surface point and a point p that is on
  /// no surface (a point light): the shadow ray stops 10⁻⁵ of the distance
  /// short of p, so a light set in a ceiling's plane is not hidden by that
  /// plane through round-off along a grazing ray (ε short is not enough there).
  bool seesPoint(const Vec3 &from, const Vec3 &fromNormal, const Vec3 &p) const;

  /// Many rays at once (Embree's stream API, coherent flag), compact results.
  void intersectMany(std::span<const Ray> rays, std::span<HitRecord> records) const;
  /// The same, completing every hit: `hits[i]` is valid where `found[i]`.
  void intersectMany(std::span<const Ray> rays, std::span<Hit> hits, std::span<uint8_t> found) const;
  /// A full Hit (double-precision position, normals, material) from a stream record.
  void completeHit(const Ray &ray, const HitRecord &record, Hit &hit) const {
    completeHit(ray, record.distance, record.triangle, record.b1, record.b2, hit);
  }

  /// Offset that lifts a ray origin off a surface: large enough to clear float
  /// round-off of Embree's copy of the geometry, small against the scene.
  double epsilon() const { return epsilon_; }
  /// A ray leaving `position` in `direction`, nudged to the side of `normal` the direction points to.
  Ray spawnRay(const Vec3 &position, const Vec3 &normal, const Vec3 &direction) const {
    return {position + normal * (dot(direction, normal) >= 0 ? epsilon_ : -epsilon_), direction};
  }

  const Scene &scene() const { return scene_; }
  RTCScene embreeScene() const { return rtcScene_; }

  /// Fills a Hit from a scene triangle and its barycentrics (used by the
  /// stream path and the benchmark; without back faces Embree's primitive
  /// ids are the scene's triangle indices).
  /// Without `interpolateNormal` the shading normal is the geometric one
  /// (intersectPosition: the vertex normals are not read).
  void completeHit(const Ray &ray, float tfar, unsigned triangle, float u, float v, Hit &hit,
                   bool interpolateNormal = true) const;

 private:
  /// The nearest hit within tMax, completed (intersect and intersectPosition).
  bool nearestHit(const Ray &ray, double tMax, bool interpolateNormal, Hit &hit) const;
  const Scene &scene_;
  RTCDevice device_ = nullptr;
  RTCScene rtcScene_ = nullptr;
  double epsilon_ = 1e-6;
  /// What completing a hit reads, per triangle, in one place: a hit touches
  /// one record instead of the triangle, three vertices and a normal.
  struct TriangleGeometry {
    Vec3 p0, edge1, edge2;  ///< vertex 0 and the edges to vertices 1 and 2
    Vec3 normal;            ///< unit front-side normal
    uint32_t material, face;
    bool hasVertexNormals;
  };
  std::vector<TriangleGeometry> geometry_;

  // Two-sided surfaces (Face::twin): Embree holds only the fronts; a hit on a
  // front triangle from behind is a hit on its face's back.
  static constexpr uint32_t kNoBack = 0xFFFFFFFFu;
  struct BackTriangles {
    uint32_t first = kNoBack, count = 0;  ///< the back face's triangles in Scene::triangles
  };
  std::vector<BackTriangles> back_;       ///< per triangle; empty when the scene has no back faces
  std::vector<uint32_t> embreeTriangle_;  ///< Embree primitive id → scene triangle; empty: the same
  /// Scene triangle and barycentrics of an Embree hit, the back's when the ray arrives from behind.
  void resolveHit(const Ray &ray, unsigned primitive, float &u, float &v, uint32_t &triangle) const;
};

}  // namespace radiant
