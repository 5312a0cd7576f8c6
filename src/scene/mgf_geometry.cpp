// MGF geometry → faces: polygons with holes (f, fh) and the tessellated
// primitives sph, cyl, cone, ring, torus and prism (docs/scene-format.md#mgf-geometry).
//
// Curved primitives are surfaces of revolution: a profile in (radius, height)
// swept around an axis in `slices` steps, each step's chord within the
// tolerance's sagitta of the circle. Polygons of more than four corners, and
// polygons with holes, are triangulated by ear clipping (Eberly, "Triangulation
// by Ear Clipping", 2002) after each hole is joined to the outline by a
// two-way bridge edge, as MGF's own parser joins them.

#include <algorithm>
#include <cmath>
#include <numeric>

#include "scene/load_detail.h"
#include "scene/mgf_detail.h"

namespace radiant::detail {
namespace {

struct Point2 {
  double u, v;
};

double cross2(const Point2 &a, const Point2 &b, const Point2 &c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

double signedArea(const std::vector<Point2> &points) {
  double area = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Point2 &a = points[i], &b = points[(i + 1) % points.size()];
    area += a.u * b.v - b.u * a.v;
  }
  return 0.5 * area;
}

/// True when segments ab and cd cross at a point inside both (not at an end).
bool segmentsCross(const Point2 &a, const Point2 &b, const Point2 &c, const Point2 &d) {
  const double d1 = cross2(a, b, c), d2 = cross2(a, b, d), d3 = cross2(c, d, a), d4 = cross2(c, d, b);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool samePlace(const Point2 &a, const Point2 &b) {
  return a.u == b.u && a.v == b.v;
}

/// Inside the counter-clockwise triangle abc or on its edges: a corner of the
/// polygon on an ear's new edge (the reflex corner of an L) makes it no ear.
bool insideTriangle(const Point2 &p, const Point2 &a, const Point2 &b, const Point2 &c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

/// Adds one point to the scene (transformed), returning its position and normal indices.
std::pair<uint32_t, int32_t> addPoint(const MgfTarget &target, const MgfPoint &point) {
  Scene &scene = target.scene;
  const auto position = static_cast<uint32_t>(scene.positions.size());
  scene.positions.push_back(target.toWorld.point(point.position));
  int32_t normal = -1;
  if (point.hasNormal && length(point.normal) > 0) {
    normal = static_cast<int32_t>(scene.normals.size());
    scene.normals.push_back(target.toWorld.normal(normalize(point.normal)));
  }
  return {position, normal};
}

void addFaceOfPoints(const MgfTarget &target, const std::vector<MgfPoint> &points) {
  std::vector<uint32_t> vertices;
  std::vector<int32_t> normals;
  bool anyNormal = false;
  for (const MgfPoint &p : points) {
    auto [v, n] = addPoint(target, p);
    vertices.push_back(v);
    normals.push_back(n);
    anyNormal = anyNormal || n >= 0;
  }
  addPolygon(target.scene, vertices, {}, anyNormal ? normals : std::vector<int32_t>{}, target.material, target.object,
             target.toWorld.determinant() < 0);
}

/// One point of a surface of revolution's profile: distance from the axis,
/// height along it, and the outward normal in (radial, axial) components.
struct ProfilePoint {
  double radius, height, normalRadial, normalAxial;
  bool smooth = true;
};

/// Sweeps `profile` around the axis through `centre` along unit `axis`. The
/// profile runs so that (slice direction × profile direction) is the front:
/// upwards along the axis for an outward cylinder, inwards for a ring facing
/// +axis. `inward` turns every face around.
void revolve(const MgfTarget &target, const Vec3 &centre, const Vec3 &axis, const std::vector<ProfilePoint> &profile,
             int slices, bool inward) {
  const Vec3 helper = std::abs(axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = normalize(cross(helper, axis)), w = cross(axis, u);
  // Rows of points, one per profile point; the last slice repeats the first.
  std::vector<std::vector<MgfPoint>> rows(profile.size(), std::vector<MgfPoint>(size_t(slices)));
  for (size_t i = 0; i < profile.size(); ++i)
    for (int j = 0; j < slices; ++j) {
      const double angle = 2 * kPi * j / slices;
      const Vec3 radial = u * std::cos(angle) + w * std::sin(angle);
      MgfPoint &p = rows[i][size_t(j)];
      p.position = centre + radial * profile[i].radius + axis * profile[i].height;
      p.normal = radial * profile[i].normalRadial + axis * profile[i].normalAxial;
      if (inward) p.normal = -p.normal;
      p.hasNormal = profile[i].smooth;
    }
  for (size_t i = 0; i + 1 < profile.size(); ++i)
    for (int j = 0; j < slices; ++j) {
      const size_t a = size_t(j), b = size_t((j + 1) % slices);
      std::vector<MgfPoint> quad = {rows[i][a], rows[i][b], rows[i + 1][b], rows[i + 1][a]};
      if (inward) std::reverse(quad.begin() + 1, quad.end());
      // addPolygon drops the repeated corner of a row on the axis (a pole, a cone's tip, a disc's centre).
      addFaceOfPoints(target, quad);
    }
}

}  // namespace

int mgfSlicesForTolerance(double tolerance) {
  // A chord of angle θ lies 1 − cos(θ/2) of the radius inside the circle.
  const double angle = 2 * std::acos(1 - std::clamp(tolerance, 1e-6, 0.5));
  int slices = static_cast<int>(std::ceil(2 * kPi / angle));
  slices = std::clamp(slices + (slices & 1), 8, 1024);
  return slices;
}

void mgfAddFace(const MgfTarget &target, const std::vector<MgfPoint> &outline,
                const std::vector<std::vector<MgfPoint>> &holes, const InputLocation &where) {
  if (holes.empty() && outline.size() <= 4) {
    addFaceOfPoints(target, outline);
    return;
  }
  // Project onto the plane that drops the Newell normal's largest component.
  Vec3 newell{0, 0, 0};
  for (size_t i = 0; i < outline.size(); ++i) {
    const Vec3 &a = outline[i].position, &b = outline[(i + 1) % outline.size()].position;
    newell = newell + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  if (!(length(newell) > 0)) {
    std::vector<Vec3> corners;
    for (const MgfPoint &p : outline) corners.push_back(p.position);
    target.scene.dropDegenerateFace(corners, target.object, "zero area");
    return;
  }
  const int drop = std::abs(newell.x) >= std::abs(newell.y) && std::abs(newell.x) >= std::abs(newell.z) ? 0
                   : std::abs(newell.y) >= std::abs(newell.z)                                           ? 1
                                                                                                        : 2;
  const int iu = (drop + 1) % 3, iv = (drop + 2) % 3;
  // Mirror u when the outline runs clockwise in this projection, so that it
  // runs counter-clockwise and a counter-clockwise triangle keeps the outline's front.
  std::vector<MgfPoint> points(outline);
  std::vector<Point2> flat;
  for (const MgfPoint &p : outline) flat.push_back({p.position[iu], p.position[iv]});
  const double mirror = signedArea(flat) < 0 ? -1 : 1;
  for (Point2 &p : flat) p.u *= mirror;

  std::vector<std::vector<Point2>> flatHoles;
  std::vector<std::vector<MgfPoint>> holePoints(holes);
  for (auto &hole : holePoints) {
    std::vector<Point2> h;
    for (const MgfPoint &p : hole) h.push_back({mirror * p.position[iu], p.position[iv]});
    if (signedArea(h) > 0) {  // holes run clockwise
      std::reverse(h.begin(), h.end());
      std::reverse(hole.begin(), hole.end());
    }
    flatHoles.push_back(std::move(h));
  }
  // Join the holes, rightmost first, each at its rightmost corner to the
  // nearest outline corner that the bridge reaches without crossing an edge.
  std::vector<size_t> order(holes.size());
  std::iota(order.begin(), order.end(), 0);
  auto rightmost = [&](size_t h) {
    return size_t(std::max_element(flatHoles[h].begin(), flatHoles[h].end(),
                                   [](const Point2 &a, const Point2 &b) { return a.u < b.u; }) -
                  flatHoles[h].begin());
  };
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return flatHoles[a][rightmost(a)].u > flatHoles[b][rightmost(b)].u; });
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t h = order[k], m = rightmost(h);
    const Point2 from = flatHoles[h][m];
    auto blocked = [&](const Point2 &to) {
      for (size_t i = 0; i < flat.size(); ++i)
        if (segmentsCross(from, to, flat[i], flat[(i + 1) % flat.size()])) return true;
      for (size_t other = k; other < order.size(); ++other) {
        const auto &ring = flatHoles[order[other]];
        for (size_t i = 0; i < ring.size(); ++i)
          if (segmentsCross(from, to, ring[i], ring[(i + 1) % ring.size()])) return true;
      }
      return false;
    };
    size_t best = flat.size();
    double bestDistance = 0;
    for (size_t i = 0; i < flat.size(); ++i) {
      const double d = sqr(flat[i].u - from.u) + sqr(flat[i].v - from.v);
      if ((best == flat.size() || d < bestDistance) && !blocked(flat[i])) best = i, bestDistance = d;
    }
    if (best == flat.size())
      throw InputError(where, "hole " + std::to_string(h + 1) + " cannot be joined to the face's outline");
    std::vector<Point2> joinedFlat(flat.begin(), flat.begin() + long(best) + 1);
    std::vector<MgfPoint> joined(points.begin(), points.begin() + long(best) + 1);
    const size_t n = flatHoles[h].size();
    for (size_t i = 0; i <= n; ++i) {
      joinedFlat.push_back(flatHoles[h][(m + i) % n]);
      joined.push_back(holePoints[h][(m + i) % n]);
    }
    joinedFlat.insert(joinedFlat.end(), flat.begin() + long(best), flat.end());
    joined.insert(joined.end(), points.begin() + long(best), points.end());
    flat = std::move(joinedFlat);
    points = std::move(joined);
  }

  std::vector<size_t> remaining(flat.size());
  std::iota(remaining.begin(), remaining.end(), 0);
  while (remaining.size() > 3) {
    const size_t n = remaining.size();
    size_t ear = n, fallback = 0;
    double fallbackCross = -1e300;
    for (size_t i = 0; i < n && ear == n; ++i) {
      const Point2 &a = flat[remaining[(i + n - 1) % n]], &b = flat[remaining[i]], &c = flat[remaining[(i + 1) % n]];
      const double turn = cross2(a, b, c);
      if (turn > fallbackCross) fallbackCross = turn, fallback = i;
      if (turn <= 0) continue;
      bool empty = true;
      for (size_t j = 0; j < n && empty; ++j) {
        const Point2 &p = flat[remaining[j]];
        if (samePlace(p, a) || samePlace(p, b) || samePlace(p, c)) continue;
        empty = !insideTriangle(p, a, b, c);
      }
      if (empty) ear = i;
    }
    if (ear == n) ear = fallback;  // only for self-intersecting input: clip the most convex corner
    addFaceOfPoints(target,
                    {points[remaining[(ear + n - 1) % n]], points[remaining[ear]], points[remaining[(ear + 1) % n]]});
    remaining.erase(remaining.begin() + long(ear));
  }
  addFaceOfPoints(target, {points[remaining[0]], points[remaining[1]], points[remaining[2]]});
}

void mgfAddSphere(const MgfTarget &target, const Vec3 &centre, double radius) {
  const int slices = mgfSlicesForTolerance(target.tolerance), stacks = slices / 2;
  const double r = std::abs(radius);
  std::vector<ProfilePoint> profile;
  for (int i = 0; i <= stacks; ++i) {
    const double polar = kPi * (1.0 - double(i) / stacks);  // from the south pole up
    profile.push_back({r * std::sin(polar), r * std::cos(polar), std::sin(polar), std::cos(polar)});
  }
  revolve(target, centre, Vec3{0, 0, 1}, profile, slices, radius < 0);
}

void mgfAddCone(const MgfTarget &target, const Vec3 &base, double baseRadius, const Vec3 &apex, double apexRadius) {
  const Vec3 along = apex - base;
  const double height = length(along);
  const Vec3 axis = along * (1 / height);
  const double r0 = std::abs(baseRadius), r1 = std::abs(apexRadius);
  // The slant's outward normal: perpendicular to the profile (r1 − r0, height).
  const double slant = std::hypot(r1 - r0, height);
  const double nr = height / slant, na = (r0 - r1) / slant;
  const std::vector<ProfilePoint> profile = {{r0, 0, nr, na}, {r1, height, nr, na}};
  revolve(target, base, axis, profile, mgfSlicesForTolerance(target.tolerance), baseRadius < 0 || apexRadius < 0);
}

void mgfAddRing(const MgfTarget &target, const Vec3 &centre, const Vec3 &axis, double innerRadius, double outerRadius) {
  // From the outer edge inwards, facing +axis; flat, so no shading normals.
  const std::vector<ProfilePoint> profile = {{outerRadius, 0, 0, 1, false}, {innerRadius, 0, 0, 1, false}};
  revolve(target, centre, normalize(axis), profile, mgfSlicesForTolerance(target.tolerance), false);
}

void mgfAddTorus(const MgfTarget &target, const Vec3 &centre, const Vec3 &axis, double innerRadius,
                 double outerRadius) {
  const bool inward = innerRadius < 0 || outerRadius < 0;
  const double rIn = std::abs(innerRadius), rOut = std::abs(outerRadius);
  const double major = 0.5 * (rIn + rOut), minor = 0.5 * (rOut - rIn);
  const int slices = mgfSlicesForTolerance(target.tolerance);
  std::vector<ProfilePoint> profile;
  for (int i = 0; i <= slices; ++i) {
    const double angle = 2 * kPi * i / slices;  // from the outer equator, over the top
    profile.push_back({major + minor * std::cos(angle), minor * std::sin(angle), std::cos(angle), std::sin(angle)});
  }
  revolve(target, centre, normalize(axis), profile, slices, inward);
}

void mgfAddPrism(const MgfTarget &target, const std::vector<Vec3> &base, double length, const InputLocation &where) {
  Vec3 newell{0, 0, 0};
  for (size_t i = 0; i < base.size(); ++i) {
    const Vec3 &a = base[i], &b = base[(i + 1) % base.size()];
    newell = newell + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  if (!(radiant::length(newell) > 0)) throw InputError(where, "prism: the base polygon has no area");
  // The far end is the base moved `length` along its normal (right-hand rule);
  // with a positive length every face looks out of the solid.
  const Vec3 offset = normalize(newell) * length;
  std::vector<MgfPoint> bottom, top;
  for (const Vec3 &p : base) {
    bottom.push_back({p, {}, false});
    top.push_back({p + offset, {}, false});
  }
  mgfAddFace(target, top, {}, where);
  std::vector<MgfPoint> reversed(bottom.rbegin(), bottom.rend());
  mgfAddFace(target, reversed, {}, where);
  for (size_t i = 0; i < base.size(); ++i) {
    const size_t j = (i + 1) % base.size();
    addFaceOfPoints(target, {bottom[i], bottom[j], top[j], top[i]});
  }
}

}  // namespace radiant::detail
