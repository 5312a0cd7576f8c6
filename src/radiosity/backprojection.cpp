#include "radiosity/backprojection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "radiosity/form_factor.h"
#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"
#include "util/sampling.h"

namespace radiant {

namespace {

struct Point2 {
  double u = 0, v = 0;
};
using Polygon2 = std::vector<Point2>;

double signedArea(const Polygon2 &p) {
  double a = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    const Point2 &s = p[k], &t = p[(k + 1) % p.size()];
    a += s.u * t.v - t.u * s.v;
  }
  return 0.5 * a;
}

struct Bounds2 {
  double uLo = INFINITY, vLo = INFINITY, uHi = -INFINITY, vHi = -INFINITY;
  explicit Bounds2(const Polygon2 &p) {
    for (const Point2 &q : p) {
      uLo = std::min(uLo, q.u), uHi = std::max(uHi, q.u);
      vLo = std::min(vLo, q.v), vHi = std::max(vHi, q.v);
    }
  }
  bool overlaps(const Bounds2 &b) const { return uLo < b.uHi && b.uLo < uHi && vLo < b.vHi && b.vLo < vHi; }
};

/// Splits a convex polygon by the directed line a → b into the part on its
/// left (inside a counter-clockwise polygon whose edge it is) and the part
/// on its right. Points within `tolerance` (a cross product, length²) of the
/// line go to both.
void splitByLine(const Polygon2 &poly, const Point2 &a, const Point2 &b, double tolerance, Polygon2 &left,
                 Polygon2 &right) {
  left.clear();
  right.clear();
  const double eu = b.u - a.u, ev = b.v - a.v;
  auto side = [&](const Point2 &p) {
    double s = eu * (p.v - a.v) - ev * (p.u - a.u);
    return std::abs(s) <= tolerance ? 0.0 : s;
  };
  for (size_t k = 0; k < poly.size(); ++k) {
    const Point2 &p = poly[k], &q = poly[(k + 1) % poly.size()];
    const double sp = side(p), sq = side(q);
    if (sp >= 0) left.push_back(p);
    if (sp <= 0) right.push_back(p);
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      const double t = sp / (sp - sq);
      const Point2 i{p.u + (q.u - p.u) * t, p.v + (q.v - p.v) * t};
      left.push_back(i);
      right.push_back(i);
    }
  }
}

/// Sutherland–Hodgman clip of a 3-D polygon to a half-space, keeping the
/// points at signed distance ≥ `keepAbove`.
void clipToHalfSpace(const std::vector<Vec3> &in, const HalfSpace &h, double keepAbove, std::vector<Vec3> &out) {
  out.clear();
  for (size_t k = 0; k < in.size(); ++k) {
    const Vec3 &a = in[k], &b = in[(k + 1) % in.size()];
    const double da = h.signedDistance(a) - keepAbove, db = h.signedDistance(b) - keepAbove;
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
}

/// What one query works on; one per thread, so queries allocate nothing
/// once warm.
struct Scratch {
  std::vector<Vec3> base, clipped, swap;
  std::vector<uint32_t> candidates;
  std::vector<Polygon2> pieces, next;
  Polygon2 projected, rest, left, right;
  std::vector<Vec3> lifted;
};

}  // namespace

DirectIrradiance::DirectIrradiance(const Scene &scene) : scene_(scene), faces_(scene) {
  const Box3 &b = faces_.sceneBounds();
  scale_ = std::max(1e-9, length(b.hi - b.lo));
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    const Face &face = scene.faces[f];
    if (!scene.materials[face.material].isEmitter()) continue;
    EmitterPolygon e;
    e.face = f;
    e.material = face.material;
    e.vertexCount = face.vertexCount;
    for (int k = 0; k < face.vertexCount; ++k) e.corners[k] = scene.positions[face.vertices[k]];
    e.normal = scene.faceNormal(face);
    e.area = scene.faceArea(face);
    e.warp = polygonWarp(std::span<const Vec3>(e.corners.data(), size_t(e.vertexCount)), e.normal);
    if (e.area > 0) emitters_.push_back(e);
  }
}

DirectIrradiance::DirectIrradiance(const Scene &scene, const RayTracer &tracer, size_t maxExactOccluders)
    : DirectIrradiance(scene) {
  tracer_ = &tracer;
  maxExactOccluders_ = maxExactOccluders;
}

double DirectIrradiance::sampledFormFactor(const Vec3 &x, const Vec3 &n, size_t emitter) const {
  const EmitterPolygon &e = emitters_[emitter];
  const double unoccluded = unoccludedFormFactor(x, n, emitter);
  if (!(unoccluded > 0) || !tracer_) return unoccluded;
  // The kernel-weighted visible fraction of a k × k grid of cell centres.
  auto fraction = [&](int k, bool &partial) {
    double all = 0, seen = 0;
    int hidden = 0, shown = 0;
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b) {
        const double u = (a + 0.5) / k, v = (b + 0.5) / k;
        Vec3 y;
        if (e.vertexCount == 4) {
          y = e.corners[0] * ((1 - u) * (1 - v)) + e.corners[1] * (u * (1 - v)) + e.corners[2] * (u * v) +
              e.corners[3] * ((1 - u) * v);
        } else {
          double b1, b2;
          sampleUniformTriangle(u, v, b1, b2);
          y = e.corners[0] * (1 - b1 - b2) + e.corners[1] * b1 + e.corners[2] * b2;
        }
        const Vec3 d = y - x;
        const double r2 = dot(d, d), towards = dot(d, n), from = -dot(d, e.normal);
        // Only the part in front of x's plane: that is all the exact factor covers.
        if (!(towards > 0 && from > 0)) continue;
        const double w = towards * from / (r2 * r2);
        all += w;
        if (tracer_->visible(x, n, y, e.normal))
          seen += w, ++shown;
        else
          ++hidden;
      }
    partial = shown > 0 && hidden > 0;
    return all > 0 ? seen / all : 0.0;
  };
  // A quarter of the rays first; where they disagree (a penumbra), the full grid.
  bool partial = false;
  double visible = fraction(kSampledVisibilityGrid / 2, partial);
  if (partial) visible = fraction(kSampledVisibilityGrid, partial);
  return unoccluded * visible;
}

double DirectIrradiance::unoccludedFormFactor(const Vec3 &x, const Vec3 &n, size_t emitter) const {
  const EmitterPolygon &e = emitters_[emitter];
  if (dot(x - e.corners[0], e.normal) <= 1e-12 * scale_ + e.warp) return 0;  // behind the emitting side (or on it)
  return formFactorPointToPolygon(x, n, std::span<const Vec3>(e.corners.data(), size_t(e.vertexCount)));
}

double visibleFormFactor(const Scene &scene, const FaceTree *tree, const std::vector<uint32_t> *occluders,
                         const Vec3 &x, const Vec3 &n, std::span<const Vec3> polygon, const Vec3 &polygonNormal,
                         int64_t skipFace, double scale, double *unoccludedOut, size_t maxOccluders) {
  if (unoccludedOut) *unoccludedOut = 0;
  const Vec3 origin = polygon[0];
  const double heightOfX = dot(x - origin, polygonNormal);
  if (heightOfX <= 1e-12 * scale + polygonWarp(polygon, polygonNormal))
    return 0;  // behind the emitting side (or on it)
  thread_local Scratch s;

  // The part of the polygon in front of x's tangent plane: the pyramid's base.
  clipToFrontHalfSpace(x, n, polygon, s.base);
  if (s.base.size() < 3) return 0;
  Vec3 baseCentre;
  for (const Vec3 &v : s.base) baseCentre += v;
  baseCentre = baseCentre / double(s.base.size());

  // The pyramid: one half-space through x and each base edge, and the
  // emitter's plane (an occluder must lie strictly between x and the emitter).
  HalfSpace pyramid[10];
  int planes = 0;
  for (size_t k = 0; k < s.base.size() && planes < 9; ++k) {
    const Vec3 &a = s.base[k], &b = s.base[(k + 1) % s.base.size()];
    Vec3 normal = cross(a - x, b - x);
    const double len = length(normal);
    if (!(len > 0)) continue;  // an edge seen end-on spans no plane
    normal = normal / len;
    if (dot(normal, baseCentre - x) < 0) normal = -normal;
    pyramid[planes++] = {normal, -dot(normal, x)};
  }
  pyramid[planes++] = {polygonNormal, -dot(polygonNormal, origin)};
  const double tolerance = 1e-9 * scale;
  if (!occluders) tree->facesInConvexRegion(pyramid, planes, tolerance, s.candidates, maxOccluders);
  const std::vector<uint32_t> &candidates = occluders ? *occluders : s.candidates;

  const double unoccluded = formFactorPointToPolygon(x, n, s.base);
  if (unoccludedOut) *unoccludedOut = unoccluded;
  if (candidates.empty() || !(unoccluded > 0)) return unoccluded;
  if (candidates.size() > maxOccluders) return -1;  // too many to subtract: the caller samples instead

  // The base in the emitter plane's 2-D frame, counter-clockwise.
  const Frame frame = Frame::fromNormal(polygonNormal);
  auto to2 = [&](const Vec3 &p) { return Point2{dot(p - origin, frame.tangent), dot(p - origin, frame.bitangent)}; };
  s.pieces.clear();
  s.pieces.emplace_back();
  for (const Vec3 &v : s.base) s.pieces.back().push_back(to2(v));
  if (signedArea(s.pieces.back()) < 0) std::reverse(s.pieces.back().begin(), s.pieces.back().end());
  const double baseArea = std::abs(signedArea(s.pieces.back()));
  const double negligibleArea = 1e-12 * baseArea;
  const double baseSize = std::sqrt(baseArea);

  bool occluded = false;
  // The tree lists the front of a two-sided pair for its back too.
  const int64_t skipGeometry = skipFace >= 0 ? int64_t(scene.geometricFace(uint32_t(skipFace))) : -1;
  for (uint32_t f : candidates) {
    if (int64_t(f) == skipFace || int64_t(f) == skipGeometry) continue;
    const Face &face = scene.faces[f];
    const Vec3 faceNormal = scene.faceNormal(face);
    // A face whose plane passes through x (x's own face, a coplanar
    // neighbour, a wall standing on x's edge) projects to a line: no area.
    // "Passes through" within the face's own warp (polygonWarp): taken as an
    // occluder, the sliver of a warped own face next to x projects over the
    // whole emitter and hides it.
    s.clipped.clear();
    for (int k = 0; k < face.vertexCount; ++k) s.clipped.push_back(scene.positions[face.vertices[k]]);
    if (std::abs(dot(x - s.clipped[0], faceNormal)) <= tolerance + polygonWarp(s.clipped, faceNormal)) continue;
    for (int h = 0; h < planes && s.clipped.size() >= 3; ++h) {
      const bool emitterPlane = h == planes - 1;
      clipToHalfSpace(s.clipped, pyramid[h], emitterPlane ? tolerance : 0.0, s.swap);
      std::swap(s.clipped, s.swap);
    }
    if (s.clipped.size() < 3) continue;
    // Central projection from x onto the emitter's plane: a point at height
    // h above it (x is at heightOfX) lands at x + (p − x)·heightOfX/(heightOfX − h).
    s.projected.clear();
    for (const Vec3 &p : s.clipped) {
      const double drop = heightOfX - dot(p - origin, polygonNormal);
      if (!(drop > 1e-15 * heightOfX)) continue;  // at the apex: already excluded by the plane test
      s.projected.push_back(to2(x + (p - x) * (heightOfX / drop)));
    }
    if (s.projected.size() < 3) continue;
    double area = signedArea(s.projected);
    if (std::abs(area) <= negligibleArea) continue;
    if (area < 0) std::reverse(s.projected.begin(), s.projected.end());
    occluded = true;

    // Subtract the projection from every visible piece: what lies outside
    // each of its edges in turn is kept, what remains inside all is hidden.
    const Bounds2 qBounds(s.projected);
    s.next.clear();
    for (Polygon2 &piece : s.pieces) {
      if (!Bounds2(piece).overlaps(qBounds)) {
        s.next.push_back(std::move(piece));
        continue;
      }
      s.rest = piece;
      for (size_t k = 0; k < s.projected.size() && s.rest.size() >= 3; ++k) {
        const Point2 &a = s.projected[k], &b = s.projected[(k + 1) % s.projected.size()];
        const double edge = std::hypot(b.u - a.u, b.v - a.v);
        splitByLine(s.rest, a, b, 1e-12 * edge * baseSize, s.left, s.right);
        if (s.right.size() >= 3 && std::abs(signedArea(s.right)) > negligibleArea) s.next.push_back(s.right);
        std::swap(s.rest, s.left);
      }
    }
    std::swap(s.pieces, s.next);
    if (s.pieces.empty()) return 0;
  }
  if (!occluded) return unoccluded;

  double visible = 0;
  for (const Polygon2 &piece : s.pieces) {
    s.lifted.clear();
    for (const Point2 &q : piece) s.lifted.push_back(origin + frame.tangent * q.u + frame.bitangent * q.v);
    visible += formFactorPointToPolygon(x, n, s.lifted);
  }
  return std::min(visible, unoccluded);
}

double DirectIrradiance::visibleFormFactor(const Vec3 &x, const Vec3 &n, size_t emitter) const {
  const EmitterPolygon &e = emitters_[emitter];
  return radiant::visibleFormFactor(scene_, &faces_, nullptr, x, n,
                                    std::span<const Vec3>(e.corners.data(), size_t(e.vertexCount)), e.normal, e.face,
                                    scale_);
}

bool DirectIrradiance::irradianceWithin(const Vec3 &x, const Vec3 &n, size_t maxOccluders, Bands &out) const {
  out = Bands(0.0);
  for (size_t k = 0; k < emitters_.size(); ++k) {
    const EmitterPolygon &e = emitters_[k];
    const double f = radiant::visibleFormFactor(scene_, &faces_, nullptr, x, n,
                                                std::span<const Vec3>(e.corners.data(), size_t(e.vertexCount)),
                                                e.normal, e.face, scale_, nullptr, maxOccluders);
    if (f < 0) return false;
    if (f > 0) out += scene_.materials[e.material].emission * (kPi * f);
  }
  if (!scene_.lights.empty()) out += pointLightIrradiance(x, n);
  return true;
}

Bands DirectIrradiance::irradiance(const Vec3 &x, const Vec3 &n) const {
  Bands h(0.0);
  for (size_t k = 0; k < emitters_.size(); ++k) {
    const EmitterPolygon &e = emitters_[k];
    const Bands &radiance = scene_.materials[e.material].emission;
    double f = radiant::visibleFormFactor(scene_, &faces_, nullptr, x, n,
                                          std::span<const Vec3>(e.corners.data(), size_t(e.vertexCount)), e.normal,
                                          e.face, scale_, nullptr, tracer_ ? maxExactOccluders_ : SIZE_MAX);
    if (f < 0) f = sampledFormFactor(x, n, k);
    if (f > 0) h += radiance * (kPi * f);
  }
  if (!scene_.lights.empty()) h += pointLightIrradiance(x, n);
  return h;
}

Bands DirectIrradiance::pointLightIrradiance(const Vec3 &x, const Vec3 &n) const {
  Bands h(0.0);
  for (const PointLight &light : scene_.lights)
    h += irradianceFrom(light, x, n, [&](const Vec3 &p, const Vec3 &) { return !segmentBlocked(x, n, p); });
  return h;
}

bool DirectIrradiance::segmentBlocked(const Vec3 &x, const Vec3 &n, const Vec3 &p) const {
  thread_local std::vector<uint32_t> candidates;
  Box3 box;
  box.extend(x);
  box.extend(p);
  const double tolerance = 1e-9 * scale_;
  // The faces whose boxes meet the segment's; past kMaxExactSegmentFaces of
  // them (a long segment over a tessellated model) one ray through the
  // tracer instead, stopped 10⁻⁵ of the way short of p like the renderers'.
  const HalfSpace sides[6] = {{{1, 0, 0}, -box.lo.x}, {{-1, 0, 0}, box.hi.x}, {{0, 1, 0}, -box.lo.y},
                              {{0, -1, 0}, box.hi.y}, {{0, 0, 1}, -box.lo.z}, {{0, 0, -1}, box.hi.z}};
  faces_.facesInConvexRegion(sides, 6, tolerance, candidates, tracer_ ? kMaxExactSegmentFaces : SIZE_MAX);
  if (tracer_ && candidates.size() > kMaxExactSegmentFaces) return !tracer_->seesPoint(x, n, p);
  const Vec3 d = p - x;
  for (uint32_t f : candidates) {
    const Face &face = scene_.faces[f];
    const Vec3 &a = scene_.positions[face.vertices[0]];
    const Vec3 normal = scene_.faceNormal(face);
    // A face whose plane holds either end (x's own face, the ceiling a
    // downlight is set in) blocks nothing.
    const double da = dot(normal, x - a), db = dot(normal, p - a);
    if (std::abs(da) <= tolerance || std::abs(db) <= tolerance || (da > 0) == (db > 0)) continue;
    const double t = da / (da - db);  // where the segment crosses the plane
    if (t <= 1e-9 || t >= 1 - 1e-9) continue;
    const Vec3 q = x + d * t;
    // Inside the (convex, planar) polygon: on the inner side of every edge.
    bool inside = true;
    for (int k = 0; k < face.vertexCount && inside; ++k) {
      const Vec3 &u = scene_.positions[face.vertices[k]];
      const Vec3 &v = scene_.positions[face.vertices[(k + 1) % face.vertexCount]];
      inside = dot(cross(v - u, q - u), normal) >= 0;
    }
    if (inside) return true;
  }
  return false;
}

Bands meanPointLightIrradiance(const DirectIrradiance &direct, const Scene &scene, std::span<const Vec3> polygon,
                               const Vec3 &normal) {
  if (polygon.size() != 3 && polygon.size() != 4) return Bands(0.0);
  // Midpoint rule on an n × n lattice, n from the polygon's size against its
  // distance to the nearest light (E varies over a scale of that distance):
  // 3 for a small far element, up to 16 for a floor under a lamp.
  double size = 0, nearest = INFINITY;
  for (size_t k = 0; k < polygon.size(); ++k)
    size = std::max(size, length(polygon[(k + 1) % polygon.size()] - polygon[k]));
  if (!(size > 0)) return Bands(0.0);
  const Vec3 centre = polygonCentroid(polygon);
  for (const PointLight &light : scene.lights)
    nearest = std::min(nearest, std::max(length(light.position - centre) - light.halfLength, 0.0));
  const int n = std::clamp(int(std::ceil(4.0 * size / std::max(nearest, 1e-9 * size))), 3, 16);
  return latticeMean(polygon, n, [&](const Vec3 &x) { return direct.pointLightIrradiance(x, normal); });
}

std::vector<Bands> pointLightIrradianceOfElements(const RayTracer &tracer, const Solution &solution) {
  const Scene &scene = tracer.scene();
  if (scene.lights.empty()) return {};
  const DirectIrradiance direct(scene, tracer, SIZE_MAX);
  const size_t n = solution.elementCount();
  std::vector<Bands> h(n, Bands(0.0));
  tbb::parallel_for(size_t(0), n, [&](size_t e) {
    const std::vector<Vec3> polygon = solution.mesh.polygon(static_cast<uint32_t>(e));
    h[e] = meanPointLightIrradiance(direct, scene, polygon, solution.mesh.normalOf(static_cast<uint32_t>(e)));
  });
  return h;
}

}  // namespace radiant
