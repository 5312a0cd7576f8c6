#include "mesh/face_split.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "raytrace/face_tree.h"
#include "util/phase.h"
#include "util/random.h"

namespace radiant {

namespace {

double polygonArea(const std::vector<Vec3> &p) {
  Vec3 sum;
  for (size_t k = 1; k + 1 < p.size(); ++k) sum += cross(p[k] - p[0], p[k + 1] - p[0]);
  return 0.5 * length(sum);
}

Vec3 polygonCentroid(const std::vector<Vec3> &p) {
  Vec3 c;
  double area = 0;
  for (size_t k = 1; k + 1 < p.size(); ++k) {
    const double a = 0.5 * length(cross(p[k] - p[0], p[k + 1] - p[0]));
    c += (p[0] + p[k] + p[k + 1]) * (a / 3);
    area += a;
  }
  return area > 0 ? c / area : p[0];
}

struct PlanarFace {
  std::vector<Vec3> polygon;
  Vec3 normal;
};

PlanarFace planarFace(const Scene &scene, uint32_t f) {
  const Face &face = scene.faces[f];
  PlanarFace p;
  for (int k = 0; k < face.vertexCount; ++k) p.polygon.push_back(scene.positions[face.vertices[k]]);
  p.normal = scene.faceNormal(face);
  return p;
}

/// Clips the segment [a, b] to a convex polygon in its plane (normal n);
/// false when nothing of it lies inside.
bool clipSegmentToPolygon(const std::vector<Vec3> &polygon, const Vec3 &n, Vec3 &a, Vec3 &b, double tolerance) {
  double t0 = 0, t1 = 1;
  const Vec3 d = b - a;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Vec3 &p = polygon[k], &q = polygon[(k + 1) % polygon.size()];
    const Vec3 inward = normalize(cross(n, q - p));
    const double start = dot(a - p, inward) + tolerance, rate = dot(d, inward);
    if (std::abs(rate) < 1e-300) {
      if (start < 0) return false;
      continue;
    }
    const double t = -start / rate;
    if (rate > 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  const Vec3 a0 = a;
  a = a0 + d * t0;
  b = a0 + d * t1;
  return true;
}

/// A candidate face: its corners (at most four) and its normal, without allocating.
struct CornerList {
  std::array<Vec3, 4> corners;
  size_t count = 0;
  Vec3 normal;
};

/// Where face g meets the plane of face f inside f: crossing or touching it,
/// or lying on it (parallel, within `gap`), outlining its part of f. A face
/// lying on f cuts it only when its area is at least `smallestLying`: each
/// of its edges splits f along the whole line (splitPieces), so the
/// thousands of millimetre facets at the foot of a tessellated sphere
/// resting on a floor cut the floor into thousands of slivers, for a hidden
/// patch far smaller than any element.
void cutsOf(const PlanarFace &f, const CornerList &g, double onPlane, double gap, double tolerance,
            double smallestLying, std::vector<CutSegment> &out) {
  std::array<double, 4> d{};
  double largest = 0, nearest = INFINITY;
  const size_t n = g.count;
  for (size_t k = 0; k < n; ++k) {
    d[k] = dot(g.corners[k] - f.polygon[0], f.normal);
    largest = std::max(largest, std::abs(d[k]));
    nearest = std::min(nearest, d[k]);
  }
  const bool inFront = nearest >= -onPlane;
  if (largest <= gap && inFront && std::abs(dot(f.normal, g.normal)) > 0.9998) {
    // Lying on f: its outline, projected onto f's plane, cuts f.
    const double area = n == 4 ? 0.5 * length(cross(g.corners[2] - g.corners[0], g.corners[3] - g.corners[1]))
                               : 0.5 * length(cross(g.corners[1] - g.corners[0], g.corners[2] - g.corners[0]));
    if (area < smallestLying) return;
    for (size_t k = 0; k < n; ++k) {
      Vec3 a = g.corners[k] - f.normal * d[k], b = g.corners[(k + 1) % n] - f.normal * d[(k + 1) % n];
      if (clipSegmentToPolygon(f.polygon, f.normal, a, b, -tolerance) && length(b - a) > tolerance)
        out.push_back({a, b});
    }
    return;
  }
  // Each corner on the plane, and each edge crossing it, gives a point: at most 2n.
  std::array<Vec3, 8> points;
  size_t found = 0;
  for (size_t k = 0; k < n; ++k) {
    const size_t m = (k + 1) % n;
    if (std::abs(d[k]) <= onPlane) points[found++] = g.corners[k] - f.normal * d[k];
    if ((d[k] > onPlane && d[m] < -onPlane) || (d[k] < -onPlane && d[m] > onPlane))
      points[found++] = g.corners[k] + (g.corners[m] - g.corners[k]) * (d[k] / (d[k] - d[m]));
  }
  if (found < 2) return;
  // The two points farthest apart (a convex face meets a plane in one segment).
  Vec3 a = points[0], b = points[1];
  double best = -1;
  for (size_t i = 0; i < found; ++i)
    for (size_t j = i + 1; j < found; ++j)
      if (const double l = length(points[j] - points[i]); l > best) best = l, a = points[i], b = points[j];
  if (best <= tolerance) return;
  if (clipSegmentToPolygon(f.polygon, f.normal, a, b, -tolerance) && length(b - a) > tolerance) out.push_back({a, b});
}

/// Splits every piece the cut passes through (its interior crossing the
/// piece's) by the cut's line: the pieces stay convex.
void splitPieces(std::vector<std::vector<Vec3>> &pieces, const CutSegment &cut, const Vec3 &n, double tolerance) {
  const Vec3 across = normalize(cross(n, cut.b - cut.a));
  std::vector<std::vector<Vec3>> result;
  for (std::vector<Vec3> &piece : pieces) {
    double lo = 0, hi = 0;
    for (const Vec3 &v : piece) {
      const double s = dot(v - cut.a, across);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    Vec3 a = cut.a, b = cut.b;
    // The cut must run through the piece, not only along its boundary or past it.
    const bool crosses = lo < -tolerance && hi > tolerance && clipSegmentToPolygon(piece, n, a, b, -tolerance) &&
                         length(b - a) > tolerance;
    if (!crosses) {
      result.push_back(std::move(piece));
      continue;
    }
    std::vector<Vec3> left, right;
    for (size_t k = 0; k < piece.size(); ++k) {
      const Vec3 &p = piece[k], &q = piece[(k + 1) % piece.size()];
      double sp = dot(p - cut.a, across), sq = dot(q - cut.a, across);
      if (std::abs(sp) <= tolerance) sp = 0;
      if (std::abs(sq) <= tolerance) sq = 0;
      if (sp >= 0) left.push_back(p);
      if (sp <= 0) right.push_back(p);
      if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
        const Vec3 x = p + (q - p) * (sp / (sp - sq));
        left.push_back(x);
        right.push_back(x);
      }
    }
    for (std::vector<Vec3> *part : {&left, &right})
      if (part->size() >= 3 && polygonArea(*part) > tolerance * tolerance) result.push_back(std::move(*part));
  }
  pieces = std::move(result);
}

/// The cosine-weighted fraction of rays from x (normal n) that meet the back of a face.
double enclosedFraction(const RayTracer &tracer, const Vec3 &x, const Vec3 &n, int rays, Pcg32 &rng) {
  const Frame frame = Frame::fromNormal(n);
  const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(double(rays)))));
  int enclosed = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      // Cosine-weighted (Malley): a uniform point of the disc, lifted.
      const double u = (i + rng.next()) / side, v = (j + rng.next()) / side;
      const double r = std::sqrt(u), phi = 2 * kPi * v;
      const Vec3 d = frame.toWorld({r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u))});
      // The back of a one-sided face. A two-sided face has no back to be
      // inside of (the ray meets its back face, Face::back, from the front):
      // its orientation is the modeller's whim, and counting its back face
      // would hide the floor of a room whose two-sided walls face outwards.
      Hit hit;
      if (tracer.intersect(tracer.spawnRay(x, n, d), hit) && dot(d, hit.geometricNormal) > 0) ++enclosed;
    }
  return double(enclosed) / (side * side);
}

/// True when, from its centre and from points two thirds of the way to each
/// corner, almost every direction meets the back of a face: the piece is
/// inside a closed object or under a panel lying on it. One point is not
/// enough: the centre of a ceiling's piece may be right above a lamp.
bool hidden(const RayTracer &tracer, const std::vector<Vec3> &piece, const Vec3 &n, const FaceSplitOptions &options,
            uint64_t seed) {
  const Vec3 centre = polygonCentroid(piece);
  Pcg32 rng(mixBits(seed), 0x5eed);
  if (enclosedFraction(tracer, centre, n, options.hiddenRays, rng) < options.hiddenFraction) return false;
  for (const Vec3 &corner : piece)
    if (enclosedFraction(tracer, centre + (corner - centre) * (2.0 / 3), n, options.hiddenRays, rng) <
        options.hiddenFraction)
      return false;
  return true;
}

}  // namespace

std::vector<std::vector<Vec3>> convexToPatches(const std::vector<Vec3> &polygon) {
  std::vector<std::vector<Vec3>> out;
  // Vertices on a straight edge (collinear with their neighbours) first: they
  // would make triangles of no area.
  std::vector<Vec3> rest;
  double size = 0;
  for (const Vec3 &v : polygon) size = std::max(size, length(v - polygon[0]));
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Vec3 &prev = polygon[(k + polygon.size() - 1) % polygon.size()], &next = polygon[(k + 1) % polygon.size()];
    if (length(cross(polygon[k] - prev, next - polygon[k])) > 1e-12 * size * size) rest.push_back(polygon[k]);
  }
  if (rest.size() < 3) return out;
  while (rest.size() > 4) {
    size_t best = 0;
    double shortest = INFINITY;
    for (size_t k = 0; k < rest.size(); ++k) {
      const double l = length(rest[(k + 1) % rest.size()] - rest[(k + rest.size() - 1) % rest.size()]);
      if (l < shortest) shortest = l, best = k;
    }
    const size_t prev = (best + rest.size() - 1) % rest.size(), next = (best + 1) % rest.size();
    out.push_back({rest[prev], rest[best], rest[next]});
    rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(best));
  }
  out.push_back(rest);
  return out;
}

std::vector<FaceSplit> splitFaces(const Scene &scene, const RayTracer &tracer, const FaceSplitOptions &options) {
  Phase phase("cutting faces where surfaces meet", scene.faces.size());
  const FaceTree tree(scene);
  const Box3 &bounds = tree.sceneBounds();
  const double extent =
      std::max({bounds.hi.x - bounds.lo.x, bounds.hi.y - bounds.lo.y, bounds.hi.z - bounds.lo.z, 1e-9});
  const double tolerance = 1e-7 * extent, onPlane = 1e-7 * extent, gap = options.coplanarGap * extent;
  std::vector<FaceSplit> splits(scene.faces.size());
  // Every face's normal once: each is a candidate for a dozen of its neighbours.
  std::vector<Vec3> normals(scene.faces.size());
  tbb::parallel_for(size_t(0), scene.faces.size(), [&](size_t f) { normals[f] = scene.faceNormal(scene.faces[f]); });
  tbb::parallel_for(size_t(0), scene.faces.size(), [&](size_t f) {
    phase.advance();
    const PlanarFace face = planarFace(scene, uint32_t(f));
    // The faces that may cut this one: those crossing or touching it, and
    // those lying within `gap` of its plane over it. Both are inside its
    // bounds widened by gap along its normal only (gap·|n| per axis): a
    // margin of gap in every direction took in every face of a finely
    // tessellated model within millimetres (about 450 candidates per face of
    // a 10⁶-triangle sphere instead of its dozen neighbours).
    Box3 box = tree.faceBounds(uint32_t(f));
    const Vec3 widen{gap * std::abs(face.normal.x), gap * std::abs(face.normal.y), gap * std::abs(face.normal.z)};
    box.lo = box.lo - widen;
    box.hi = box.hi + widen;
    std::vector<uint32_t> near;
    tree.facesOverlapping(box, tolerance, near);
    const double smallestLying = options.smallestLyingFraction * polygonArea(face.polygon);
    std::vector<CutSegment> cuts;
    for (uint32_t g : near) {
      if (g == f || g == scene.geometricFace(uint32_t(f)) || int64_t(g) == scene.faces[f].twin) continue;
      const Face &other = scene.faces[g];
      CornerList corners;
      corners.count = size_t(other.vertexCount);
      for (size_t k = 0; k < corners.count; ++k) corners.corners[k] = scene.positions[other.vertices[k]];
      corners.normal = normals[g];
      cutsOf(face, corners, onPlane, gap, tolerance, smallestLying, cuts);
    }
    if (cuts.empty()) return;
    std::vector<std::vector<Vec3>> pieces{face.polygon};
    for (const CutSegment &cut : cuts) splitPieces(pieces, cut, face.normal, tolerance);
    if (pieces.size() <= 1) return;  // every cut along the boundary: nothing to do
    FaceSplit &split = splits[f];
    split.cuts = std::move(cuts);
    for (size_t k = 0; k < pieces.size(); ++k) {
      if (hidden(tracer, pieces[k], face.normal, options, (uint64_t(f) << 20) ^ k))
        ++split.hiddenPieces;
      else
        split.pieces.push_back(std::move(pieces[k]));
    }
  });
  return splits;
}

}  // namespace radiant
