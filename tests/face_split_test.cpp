// Faces cut where other surfaces meet them (mesh/face_split.h): the cuts, the
// hidden pieces, the convex patches they become, and patchAt on the result.
// The expected answers are geometry computed from the scene itself (areas,
// footprints), so the tolerances are round-off on metre-sized polygons, plus
// the cutter's own snapping of 1e-7 of the scene's extent where stated.
#include "mesh/face_split.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"
#include "scene/load_scene.h"
#include "test_scenes.h"
#include "util/random.h"

namespace radiant {
namespace {

double polygonArea(const std::vector<Vec3> &p) {
  Vec3 sum;
  for (size_t k = 1; k + 1 < p.size(); ++k) sum += cross(p[k] - p[0], p[k + 1] - p[0]);
  return 0.5 * length(sum);
}

/// Signed distance of x inside the convex polygon (normal n, counter-clockwise
/// about n): the smallest distance to an edge's line, negative outside.
double depthInside(const std::vector<Vec3> &polygon, const Vec3 &n, const Vec3 &x) {
  double depth = INFINITY;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Vec3 &a = polygon[k], &b = polygon[(k + 1) % polygon.size()];
    depth = std::min(depth, dot(x - a, normalize(cross(n, b - a))));
  }
  return depth;
}

/// Convex and counter-clockwise about n: every corner turns left (collinear corners allowed).
bool convexAbout(const std::vector<Vec3> &p, const Vec3 &n, double tolerance) {
  for (size_t k = 0; k < p.size(); ++k) {
    const Vec3 &a = p[k], &b = p[(k + 1) % p.size()], &c = p[(k + 2) % p.size()];
    if (dot(cross(b - a, c - b), n) < -tolerance) return false;
  }
  return true;
}

std::vector<Vec3> facePolygon(const Scene &scene, uint32_t f) {
  std::vector<Vec3> p;
  for (int k = 0; k < scene.faces[f].vertexCount; ++k) p.push_back(scene.positions[scene.faces[f].vertices[k]]);
  return p;
}

uint32_t faceOf(const Scene &scene, const std::string &object) {
  for (uint32_t f = 0; f < scene.faces.size(); ++f)
    if (scene.objects[scene.faces[f].object].name == object) return f;
  ADD_FAILURE() << "no object " << object;
  return 0;
}

/// A polygon projected straight down onto the plane y = 0 (the Cornell floor's).
std::vector<Vec3> onFloor(std::vector<Vec3> p) {
  for (Vec3 &v : p) v.y = 0;
  return p;
}

/// Adds a quad over four new positions, counter-clockwise seen from its front.
void addQuad(Scene &s, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const uint32_t first = static_cast<uint32_t>(s.positions.size());
  s.positions.insert(s.positions.end(), {a, b, c, d});
  Face f;
  f.vertexCount = 4;
  for (uint32_t i = 0; i < 4; ++i) f.vertices[i] = first + i;
  s.addFace(f);
}

Scene emptyScene() {
  Scene s;
  s.objects.push_back({"test", "test"});
  Material m;
  m.diffuse = Bands(0.5);
  s.materials = {m};
  return s;
}

/// The floor [0, 2] × [0, 1] at y = 0 facing up (face 0).
Scene floorScene() {
  Scene s = emptyScene();
  addQuad(s, {0, 0, 0}, {0, 0, 1}, {2, 0, 1}, {2, 0, 0});
  return s;
}

/// Random points of a face (planar quad or triangle) by its bilinear / barycentric map.
Vec3 pointOnPolygon(const std::vector<Vec3> &p, double u, double v) {
  if (p.size() == 4) return p[0] * ((1 - u) * (1 - v)) + p[1] * (u * (1 - v)) + p[2] * (u * v) + p[3] * ((1 - u) * v);
  if (u + v > 1) u = 1 - u, v = 1 - v;
  return p[0] * (1 - u - v) + p[1] * u + p[2] * v;
}

/// The visible pieces of a split face, with the regions `hiddenRegions`
/// (convex, in the face's plane), tile the face: a random point of the face is
/// in exactly one piece when outside every hidden region and in none inside
/// one. Points within `margin` of a boundary are not judged. Fails on
/// overlapping or missing pieces, or a hidden piece that is not the region.
void expectPiecesTileTheFaceAroundHoles(const Scene &scene, uint32_t f, const FaceSplit &split,
                                        const std::vector<std::vector<Vec3>> &hiddenRegions) {
  const std::vector<Vec3> face = facePolygon(scene, f);
  const Vec3 n = scene.faceNormal(scene.faces[f]);
  const double margin = 1e-6;
  Pcg32 rng(f + 1, 17);
  int judged = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Vec3 x = pointOnPolygon(face, rng.next(), rng.next());
    bool nearEdge = false, inHole = false;
    for (const auto &h : hiddenRegions) {
      const double d = depthInside(h, n, x);
      nearEdge |= std::abs(d) < margin;
      inHole |= d > 0;
    }
    int inside = 0;
    for (const auto &piece : split.pieces) {
      const double d = depthInside(piece, n, x);
      nearEdge |= std::abs(d) < margin;
      inside += d > 0;
    }
    if (nearEdge) continue;
    ++judged;
    ASSERT_EQ(inside, inHole ? 0 : 1) << "point " << x.x << " " << x.y << " " << x.z;
  }
  EXPECT_GT(judged, 3900);
}

TEST(FaceSplit, CornellFloorHidesExactlyTheBlockFootprints) {
  // The blocks stand on the floor: their sides' feet cut it, and the two
  // footprints (the blocks' tops projected down: the sides are vertical) are
  // hidden inside the closed blocks. Fails if a footprint were kept (it would
  // darken and dim the floor around it) or a visible part dropped or doubled.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  const uint32_t floor = faceOf(scene, "floor");
  const FaceSplit &split = splits[floor];
  EXPECT_EQ(split.hiddenPieces, 2u);
  ASSERT_GE(split.pieces.size(), 4u);
  const double floorArea = scene.faceArea(scene.faces[floor]);
  const double footprints = scene.faceArea(scene.faces[faceOf(scene, "short-block-top")]) +
                            scene.faceArea(scene.faces[faceOf(scene, "tall-block-top")]);
  double visible = 0;
  const Vec3 n = scene.faceNormal(scene.faces[floor]);
  for (const auto &piece : split.pieces) {
    visible += polygonArea(piece);
    EXPECT_TRUE(convexAbout(piece, n, 1e-12)) << "a piece is not convex and counter-clockwise";
  }
  EXPECT_NEAR(visible, floorArea - footprints, 1e-6 * floorArea);
  expectPiecesTileTheFaceAroundHoles(scene, floor, split,
                                     {onFloor(facePolygon(scene, faceOf(scene, "short-block-top"))),
                                      onFloor(facePolygon(scene, faceOf(scene, "tall-block-top")))});
}

TEST(FaceSplit, CornellCeilingHidesTheLightsOutline) {
  // The light hangs 0.1 mm under the ceiling, parallel, facing the same way:
  // its outline cuts the ceiling and the part above it is hidden behind the
  // light's back. Fails if the coplanar-gap test missed it (the ceiling would
  // keep an element in the dark above the light).
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  const uint32_t ceiling = faceOf(scene, "ceiling"), light = faceOf(scene, "light");
  EXPECT_EQ(splits[ceiling].hiddenPieces, 1u);
  double visible = 0;
  for (const auto &piece : splits[ceiling].pieces) visible += polygonArea(piece);
  const double area = scene.faceArea(scene.faces[ceiling]);
  EXPECT_NEAR(visible, area - scene.faceArea(scene.faces[light]), 1e-6 * area);
  std::vector<Vec3> outline = facePolygon(scene, light);
  for (Vec3 &v : outline) v.y = scene.positions[scene.faces[ceiling].vertices[0]].y;
  expectPiecesTileTheFaceAroundHoles(scene, ceiling, splits[ceiling], {outline});
}

TEST(FaceSplit, CornellFacesMeetingOnlyAlongEdgesAreNotSplit) {
  // The walls meet the floor, ceiling and each other along their edges, the
  // blocks' sides meet the floor along theirs and each other at corners, the
  // left wall's two triangles share their diagonal, and the light does not
  // touch the ceiling (it is behind the light's back): none of these is cut.
  // Fails if a cut along an edge split a face (slivers) or made pieces.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    const std::string &name = scene.objects[scene.faces[f].object].name;
    if (name == "floor" || name == "ceiling") continue;
    EXPECT_FALSE(splits[f].split()) << name;
    EXPECT_TRUE(splits[f].pieces.empty()) << name;
  }
}

TEST(FaceSplit, ADividerPiercingAFloorCutsItAlongItsFootAndHidesNothing) {
  // A vertical divider at x = 1 through the floor (it reaches 0.5 m below and
  // beyond both edges): the floor is cut along its foot into a piece on each
  // side, both visible (each sees half a hemisphere open). Fails if the cut
  // were missed (one element row straddling the divider: the leak) or a side
  // taken for hidden.
  Scene scene = floorScene();
  addQuad(scene, {1, -0.5, -0.5}, {1, 1, -0.5}, {1, 1, 1.5}, {1, -0.5, 1.5});  // facing −x
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  const FaceSplit &split = splits[0];
  EXPECT_EQ(split.hiddenPieces, 0u);
  ASSERT_EQ(split.pieces.size(), 2u);
  double area = 0;
  int left = 0, right = 0;
  const double snap = 1e-7 * 2 * 1.01;  // the cutter's tolerance: 1e-7 of the extent (2 m)
  for (const auto &piece : split.pieces) {
    area += polygonArea(piece);
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3 &v : piece) lo = std::min(lo, v.x), hi = std::max(hi, v.x);
    EXPECT_TRUE(hi <= 1 + 1e-12 || lo >= 1 - 1e-12) << "a piece straddles the divider";
    left += hi <= 1 + 1e-12, right += lo >= 1 - 1e-12;
  }
  EXPECT_EQ(left, 1);
  EXPECT_EQ(right, 1);
  EXPECT_NEAR(area, 2.0, 1e-12);
  bool foot = false;
  for (const CutSegment &c : split.cuts)
    foot |= std::abs(c.a.x - 1) < 1e-12 && std::abs(c.b.x - 1) < 1e-12 && std::abs(c.a.y) < 1e-12 &&
            std::abs(c.b.y) < 1e-12 && std::min(c.a.z, c.b.z) < snap && std::max(c.a.z, c.b.z) > 1 - snap;
  EXPECT_TRUE(foot) << "no cut runs along the divider's foot, z from 0 to 1";
  // The divider itself is cut by the floor across it, into parts above and below; none is hidden.
  EXPECT_EQ(splits[1].hiddenPieces, 0u);
  EXPECT_EQ(splits[1].pieces.size(), 2u);
}

TEST(FaceSplit, NodesAlongTheDividersFootAreNeverPooledAcrossIt) {
  // The mesh of the pierced floor: every node on the foot is marked on the
  // cut, so node values (Solution::nodeValues, which pools coincident nodes
  // of one smooth surface) keep each side's own value. With 1 on the
  // elements left of the divider and 0 right of it, every node must read
  // exactly its side's value. Fails if a node on the foot were pooled with
  // its twin across the divider (it would read ½: light leaking under it).
  Scene scene = floorScene();
  addQuad(scene, {1, -0.5, -0.5}, {1, 1, -0.5}, {1, 1, 1.5}, {1, -0.5, 1.5});
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  MeshOptions options;
  options.maxEdgeLength = 0.25;
  options.faceSplits = &splits;
  Solution s = initialSolution(scene, buildMesh(scene, options));
  std::vector<Bands> side(s.elementCount());
  for (uint32_t e = 0; e < s.elementCount(); ++e)
    side[e] = Bands(s.mesh.patchOf(e).face == 0 && s.mesh.elements[e].centre.x < 1 ? 1.0 : 0.0);
  const std::vector<Bands> values = s.nodeValues(side);
  int onFoot = 0;
  for (uint32_t v = 0; v < s.mesh.nodes.size(); ++v) {
    const Patch &p = s.mesh.patches[s.mesh.nodePatch[v]];
    if (p.face != 0) continue;
    double centreX = 0;
    for (int k = 0; k < p.vertexCount; ++k) centreX += p.corners[k].x / p.vertexCount;
    const Vec3 &x = s.mesh.nodes[v];
    EXPECT_EQ(values[v][0], centreX < 1 ? 1.0 : 0.0) << "floor node at x " << x.x << ", z " << x.z;
    if (std::abs(x.x - 1) < 1e-12) {
      ++onFoot;
      EXPECT_TRUE(s.mesh.nodeOnCut[v]) << "floor node on the divider's foot at z " << x.z << " is not marked";
    }
  }
  EXPECT_EQ(onFoot, 2 * 5);  // 4 elements along the foot of 1 m at 0.25 m, on each side
}

TEST(FaceSplit, ABoxStandingOnAFloorHidesExactlyItsFootprint) {
  // Five faces facing out, no bottom, turned 30° about y, on the floor: its
  // sides' feet cut the floor, and the footprint (0.6 × 0.4 m) is inside the
  // box, hidden. Fails if the footprint were kept, or more than it hidden.
  Scene scene = emptyScene();
  addQuad(scene, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});  // the floor, facing up
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6), h = 0.5;
  auto at = [&](double x, double y, double z) { return Vec3{0.1 + c * x + s * z, y, 0.05 - s * x + c * z}; };
  const double a = 0.3, b = 0.2;
  addQuad(scene, at(-a, h, -b), at(-a, h, b), at(a, h, b), at(a, h, -b));  // top, facing up
  addQuad(scene, at(a, 0, -b), at(a, h, -b), at(a, h, b), at(a, 0, b));    // +x side
  addQuad(scene, at(-a, 0, -b), at(-a, 0, b), at(-a, h, b), at(-a, h, -b));
  addQuad(scene, at(-a, 0, b), at(a, 0, b), at(a, h, b), at(-a, h, b));  // +z side
  addQuad(scene, at(-a, 0, -b), at(-a, h, -b), at(a, h, -b), at(a, 0, -b));
  const Vec3 centre = at(0, h / 2, 0);
  for (uint32_t f = 1; f < 6; ++f) {  // all face outwards
    const std::vector<Vec3> p = facePolygon(scene, f);
    EXPECT_GT(dot(scene.faceNormal(scene.faces[f]), (p[0] + p[2]) * 0.5 - centre), 0) << "face " << f;
  }
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  EXPECT_EQ(splits[0].hiddenPieces, 1u);
  double visible = 0;
  for (const auto &piece : splits[0].pieces) visible += polygonArea(piece);
  EXPECT_NEAR(visible, 4.0 - 4 * a * b, 1e-9);
  expectPiecesTileTheFaceAroundHoles(scene, 0, splits[0], {{at(-a, 0, -b), at(-a, 0, b), at(a, 0, b), at(a, 0, -b)}});
  for (uint32_t f = 1; f < 6; ++f) EXPECT_FALSE(splits[f].split()) << "box face " << f;
}

TEST(FaceSplit, AQuadJustAboveALargerOneHidesItsOutlinesPart) {
  // A 0.3 × 0.5 m panel 0.1 mm above a 1 m² quad, both facing up (a rug on a
  // floor; the gap is within coplanarGap = 1e-3 of the 1 m extent): the lower
  // one is cut along the panel's outline and the part under it is hidden
  // behind the panel's back. The panel itself is not cut (the lower quad is
  // behind it). Fails if the outline were not projected onto the lower
  // plane, or the part under the panel were kept.
  Scene scene = emptyScene();
  addQuad(scene, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  const double y = 1e-4;
  addQuad(scene, {0.3, y, 0.2}, {0.3, y, 0.7}, {0.6, y, 0.7}, {0.6, y, 0.2});
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  EXPECT_EQ(splits[0].hiddenPieces, 1u);
  double visible = 0;
  for (const auto &piece : splits[0].pieces) visible += polygonArea(piece);
  EXPECT_NEAR(visible, 1.0 - 0.15, 1e-9);
  expectPiecesTileTheFaceAroundHoles(scene, 0, splits[0],
                                     {{{0.3, 0, 0.2}, {0.3, 0, 0.7}, {0.6, 0, 0.7}, {0.6, 0, 0.2}}});
  EXPECT_FALSE(splits[1].split());
}

TEST(FaceSplit, AnExactlyDuplicatedFaceHidesNothingOfItsTwin) {
  // Two identical quads in the same place (a modelling slip). Each lies on
  // the other within the gap, so each one's outline is offered as a cut of
  // the other, but it runs along the face's own boundary and cuts nothing:
  // both faces stay whole and nothing is hidden (each is meshed as if the
  // other were not there; the ray tracer picks one per ray). Fails if the
  // twin were taken for a panel lying on the face and the whole face hidden
  // (then both would vanish from the mesh).
  Scene scene = emptyScene();
  addQuad(scene, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  addQuad(scene, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  for (int f = 0; f < 2; ++f) {
    EXPECT_FALSE(splits[f].split()) << "face " << f;
    EXPECT_EQ(splits[f].hiddenPieces, 0u);
  }
  MeshOptions options;
  options.faceSplits = &splits;
  RadiosityMesh mesh = buildMesh(scene, options);
  EXPECT_GE(mesh.patchOfFace[0], 0);
  EXPECT_GE(mesh.patchOfFace[1], 0);
}

TEST(FaceSplit, ConvexToPatchesMakesConvexTrianglesAndQuadsOfTheSameArea) {
  // Random convex polygons of 3–12 vertices (on an ellipse in a random plane):
  // every output polygon has 3 or 4 vertices, is convex and counter-clockwise
  // like the input, has positive area, and the areas sum to the input's.
  // Fails on a piece lost or doubled, a reflex or reversed piece, or one of
  // more than 4 vertices (the mesher subdivides only quads and triangles).
  Pcg32 rng(3, 5);
  for (int trial = 0; trial < 500; ++trial) {
    const int count = 3 + trial % 10;
    const Vec3 n = normalize(Vec3{rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5});
    const Frame frame = Frame::fromNormal(n);
    const double ra = 0.1 + rng.next(), rb = 0.1 + rng.next();
    std::vector<double> angles;
    for (int k = 0; k < count; ++k) angles.push_back(2 * kPi * rng.next());
    std::sort(angles.begin(), angles.end());
    std::vector<Vec3> polygon;
    const Vec3 origin{rng.next(), rng.next(), rng.next()};
    for (double t : angles) polygon.push_back(origin + frame.toWorld({ra * std::cos(t), rb * std::sin(t), 0}));
    const double area = polygonArea(polygon);
    if (area < 1e-6) continue;
    double sum = 0;
    for (const std::vector<Vec3> &p : convexToPatches(polygon)) {
      ASSERT_TRUE(p.size() == 3 || p.size() == 4) << p.size() << " vertices";
      EXPECT_TRUE(convexAbout(p, n, 1e-12)) << "trial " << trial;
      Vec3 orientation;
      for (size_t k = 1; k + 1 < p.size(); ++k) orientation += cross(p[k] - p[0], p[k + 1] - p[0]);
      EXPECT_GT(dot(orientation, n), 0) << "trial " << trial << ": a reversed or empty piece";
      sum += polygonArea(p);
    }
    EXPECT_NEAR(sum, area, 1e-12 * (1 + area)) << "trial " << trial;
  }
}

TEST(FaceSplit, PatchAtOnTheCornellFloorFindsThePatchContainingThePoint) {
  // The floor's patches (the quads and triangles of its visible pieces): for
  // random points of the floor outside the footprints, patchAt names a patch
  // of the floor containing the point, and locate an element whose nodes'
  // weights give the point back. Points a micrometre inside a patch's edge
  // must find that patch, not its neighbour across the edge. Fails if the
  // lookup grid missed a patch (it would return the face's first patch) or
  // the depth test preferred a neighbour.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  MeshOptions options;
  options.maxEdgeLength = 0.1;
  options.faceSplits = &splits;
  const RadiosityMesh mesh = buildMesh(scene, options);
  const uint32_t floor = faceOf(scene, "floor");
  ASSERT_GT(mesh.facePatchCount[floor], 4u);
  const Vec3 n = scene.faceNormal(scene.faces[floor]);
  const std::vector<std::vector<Vec3>> footprints = {onFloor(facePolygon(scene, faceOf(scene, "short-block-top"))),
                                                     onFloor(facePolygon(scene, faceOf(scene, "tall-block-top")))};
  auto polygonOf = [&](const Patch &p) {
    return std::vector<Vec3>(p.corners.begin(), p.corners.begin() + p.vertexCount);
  };
  auto check = [&](const Vec3 &x, int32_t expected) {
    const int32_t p = mesh.patchAt(floor, x);
    ASSERT_GE(p, 0);
    EXPECT_EQ(mesh.patches[p].face, floor);
    EXPECT_GT(depthInside(polygonOf(mesh.patches[p]), n, x), -1e-12) << "at " << x.x << " " << x.z;
    if (expected >= 0) {
      EXPECT_EQ(p, expected);
    }
    const MeshLocation l = mesh.locate(floor, x);
    EXPECT_EQ(mesh.elements[l.element].patch, uint32_t(p));
    const std::array<double, 4> w = mesh.nodeWeights(l);
    Vec3 back;
    for (int k = 0; k < mesh.elements[l.element].vertexCount; ++k)
      back += mesh.nodes[mesh.elements[l.element].nodes[k]] * w[k];
    EXPECT_LT(length(back - x), 1e-9);
  };
  Pcg32 rng(21, 2);
  const std::vector<Vec3> face = facePolygon(scene, floor);
  int tested = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 x = pointOnPolygon(face, rng.next(), rng.next());
    bool outside = true;
    for (const auto &f : footprints) outside &= depthInside(f, n, x) < -1e-6;
    if (!outside) continue;
    check(x, -1);
    ++tested;
  }
  EXPECT_GT(tested, 2300);  // the footprints are 18 % of the floor
  const uint32_t first = static_cast<uint32_t>(mesh.patchOfFace[floor]);
  for (uint32_t p = first; p < first + mesh.facePatchCount[floor]; ++p) {
    const std::vector<Vec3> poly = polygonOf(mesh.patches[p]);
    for (size_t k = 0; k < poly.size(); ++k) {
      const Vec3 a = poly[k], b = poly[(k + 1) % poly.size()];
      for (double t : {0.1, 0.5, 0.9})
        check(a + (b - a) * t + normalize(cross(n, b - a)) * 1e-6, static_cast<int32_t>(p));
    }
  }
}

}  // namespace
}  // namespace radiant
