#include "scene/overlapping_faces.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

namespace radiant {

namespace {

using Point2 = std::array<double, 2>;
using Polygon2 = std::vector<Point2>;

double signedArea(const Polygon2 &p) {
  double twice = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    const Point2 &a = p[k], &b = p[(k + 1) % p.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * twice;
}

/// Sutherland–Hodgman: the part of `subject` inside the convex,
/// counter-clockwise `clip`.
Polygon2 clipConvex(Polygon2 subject, const Polygon2 &clip) {
  for (size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Point2 &a = clip[e], &b = clip[(e + 1) % clip.size()];
    auto side = [&](const Point2 &p) { return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]); };
    Polygon2 out;
    for (size_t k = 0; k < subject.size(); ++k) {
      const Point2 &p = subject[k], &q = subject[(k + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
    subject = std::move(out);
  }
  return subject;
}

struct PlanarFace {
  uint32_t face;
  Polygon2 outline;  ///< counter-clockwise in the plane's projection
  double area, minX, maxX, minY, maxY;
};

}  // namespace

std::vector<FaceOverlap> findOverlappingFaces(const Scene &scene, size_t maxPairs) {
  std::vector<FaceOverlap> found;
  if (scene.faces.size() < 2 || maxPairs == 0) return found;
  Vec3 lo = scene.positions.front(), hi = lo;
  for (const Vec3 &p : scene.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double size = std::max(length(hi - lo), 1e-12);

  // Faces grouped by their plane: quantised normal and offset.
  std::map<std::array<long long, 4>, std::vector<uint32_t>> byPlane;
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    const Face &face = scene.faces[f];
    const Vec3 n = scene.faceNormal(face);
    if (!isFinite(n)) continue;
    const double offset = dot(n, scene.positions[face.vertices[0]]);
    byPlane[{std::llround(n.x * 1e6), std::llround(n.y * 1e6), std::llround(n.z * 1e6),
             std::llround(offset / (size * 1e-7))}]
        .push_back(f);
  }
  for (const auto &[plane, faces] : byPlane) {
    if (faces.size() < 2) continue;
    // Project onto the two axes the normal is least along.
    const Vec3 n = scene.faceNormal(scene.faces[faces[0]]);
    const int drop = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0
                     : std::abs(n.y) >= std::abs(n.z)                                 ? 1
                                                                                      : 2;
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    std::vector<PlanarFace> planar;
    for (uint32_t f : faces) {
      const Face &face = scene.faces[f];
      PlanarFace p{f, {}, 0, INFINITY, -INFINITY, INFINITY, -INFINITY};
      for (int k = 0; k < face.vertexCount; ++k) {
        const Vec3 &q = scene.positions[face.vertices[k]];
        p.outline.push_back({q[u], q[v]});
        p.minX = std::min(p.minX, q[u]), p.maxX = std::max(p.maxX, q[u]);
        p.minY = std::min(p.minY, q[v]), p.maxY = std::max(p.maxY, q[v]);
      }
      p.area = signedArea(p.outline);
      if (p.area < 0) std::reverse(p.outline.begin(), p.outline.end()), p.area = -p.area;
      if (p.area > 0) planar.push_back(std::move(p));
    }
    // Sweep along the first axis: only faces whose extents overlap are compared.
    std::sort(planar.begin(), planar.end(), [](const PlanarFace &a, const PlanarFace &b) { return a.minX < b.minX; });
    for (size_t i = 0; i < planar.size() && found.size() < maxPairs; ++i)
      for (size_t j = i + 1; j < planar.size() && planar[j].minX < planar[i].maxX; ++j) {
        const PlanarFace &a = planar[i], &b = planar[j];
        if (b.minY >= a.maxY || a.minY >= b.maxY) continue;
        const double shared = std::abs(signedArea(clipConvex(a.outline, b.outline)));
        // Scene::faceArea is in the plane; the projection shrinks both alike.
        // Not below 10⁻³ of the smaller face: a mesh stored in single precision (glTF, an exported
        // radiosity mesh) puts a vertex on a neighbour's edge up to ~10⁻⁷ of the scene's size off it,
        // and the slivers that makes (up to 1.2·10⁻⁴ of a small face, seen) are no copy of a face.
        if (!(shared > 1e-3 * std::min(a.area, b.area))) continue;
        const double scale = scene.faceArea(scene.faces[a.face]) / a.area;
        found.push_back({std::min(a.face, b.face), std::max(a.face, b.face), shared * scale});
        if (found.size() >= maxPairs) break;
      }
    if (found.size() >= maxPairs) break;
  }
  std::sort(found.begin(), found.end(), [](const FaceOverlap &a, const FaceOverlap &b) {
    return std::tie(a.first, a.second) < std::tie(b.first, b.second);
  });
  return found;
}

std::string describeOverlappingFaces(const Scene &scene, const std::vector<FaceOverlap> &overlaps) {
  if (overlaps.empty()) return "";
  const FaceOverlap &o = overlaps.front();
  auto objectOf = [&](uint32_t face) {
    const uint32_t object = scene.faces[face].object;
    return object < scene.objects.size() ? scene.objects[object].name : std::string("?");
  };
  // A face number is nothing a modeller shows: each face is also placed by its centroid, in the
  // scene's units (the JSON "units"; metres beside them when those are not metres).
  auto centroidOf = [&](uint32_t face) {
    const Face &f = scene.faces[face];
    Vec3 sum;
    for (int k = 0; k < f.vertexCount; ++k) sum = sum + scene.positions[f.vertices[k]];
    const Vec3 metres = sum * (1.0 / f.vertexCount);
    const Vec3 units = metres * (1.0 / scene.metresPerUnit);
    if (scene.metresPerUnit == 1.0) return fmt::format("at ({:.4g}, {:.4g}, {:.4g}) m", metres.x, metres.y, metres.z);
    return fmt::format("at ({:.4g}, {:.4g}, {:.4g}) in scene units, ({:.4g}, {:.4g}, {:.4g}) m", units.x, units.y,
                       units.z, metres.x, metres.y, metres.z);
  };
  return fmt::format(
      "{} pair{} of faces overlap in one plane, facing the same way (the first: face {} of object "
      "'{}' {} and face {} of '{}' {}, sharing {:.3g} m²)",
      overlaps.size(), overlaps.size() == 1 ? "" : "s", o.first, objectOf(o.first), centroidOf(o.first), o.second,
      objectOf(o.second), centroidOf(o.second), o.area);
}

}  // namespace radiant
