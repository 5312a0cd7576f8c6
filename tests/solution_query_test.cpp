// Reading the solution at a point (radiosity/solution_query.h): the front-side
// rule, C&W eq. 9.11's texture factor, the one clamping rule, the direct and
// indirect fields, the links that light a leaf; and the point-to-polygon
// form factor with visibility (radiosity/form_factor.h) the gathers share.
#include "radiosity/solution_query.h"

#include <gtest/gtest.h>

#include <set>

#include "radiosity/form_factor.h"
#include "radiosity/solver.h"
#include "scene/load_scene.h"
#include "test_scenes.h"
#include "util/sampling.h"

namespace radiant {
namespace {

/// The unit square in the plane y = 0, facing +y, as one patch of one
/// element, with the solution's values set by hand: B, E and ρ̄ uniform, so
/// the interpolated values equal the element's at every point.
struct OneElement {
  Scene scene;
  Solution solution;
  OneElement(const Bands &radiosity, const Bands &emission, const Bands &meanReflectance, bool textured) {
    scene.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}};
    scene.objects.push_back({"square", "test"});
    Material m;
    m.name = "square";
    m.diffuse = meanReflectance;
    scene.materials.push_back(m);
    test::addQuads(scene, {0});
    MeshOptions options;
    options.maxEdgeLength = 2.0;
    solution = initialSolution(scene, buildMesh(scene, options));
    EXPECT_EQ(solution.elementCount(), 1u);
    solution.reflectance[0] = meanReflectance;
    solution.emission[0] = emission;
    solution.radiosity[0] = radiosity;
    solution.updateNodesAndErrors();
    // Only the index matters to the reading (ρ(x) is the caller's): no image
    // behind it, so set after meshing, which would average it over the element.
    if (textured) scene.materials[0].diffuseTextureIndex = 0;
  }
  Hit hitFrom(double y) const {
    RayTracer tracer(scene);
    Hit hit;
    EXPECT_TRUE(tracer.intersect(Ray{{0.3, y, 0.6}, {0, y > 0 ? -1.0 : 1.0, 0}}, hit));
    return hit;
  }
};

// Eq. 9.11: at a point of texture value ρ(x) the reflected radiosity is
// (B − E)·ρ(x)/ρ̄, the emission unscaled; where ρ̄ = 0 (band 2) nothing.
TEST(SolutionQuery, ATexturedPointReflectsRhoOverTheMeanTimesBMinusE) {
  OneElement square(Bands(2.0, 2.0, 0.5), Bands(0.5), Bands(0.4, 0.4, 0.0), true);
  const Hit hit = square.hitFrom(1);
  SolutionPoint at;
  ASSERT_TRUE(locateHit(square.solution, hit, {0, 1, 0}, at));
  const Bands rho(0.6, 0.1, 0.3);
  applySurfaceDetail(square.solution, square.scene.materials[0], rho, at);
  const Bands reflected = reflectedRadiosity(square.solution, at);
  EXPECT_NEAR(reflected[0], 0.6 / 0.4 * 1.5, 1e-12);
  EXPECT_NEAR(reflected[1], 0.1 / 0.4 * 1.5, 1e-12);
  EXPECT_EQ(reflected[2], 0.0);
  const Bands b = radiosity(square.solution, at);
  EXPECT_NEAR(b[0], 0.5 + 2.25, 1e-12);
  EXPECT_NEAR(b[2], 0.5, 1e-12);  // emission is never scaled
  EXPECT_NEAR(reflectedRadiance(square.solution, at)[0], 2.25 * kInvPi, 1e-12);
  // The element's own ρ̄ for the constant display: the same here, where ρ̄ is uniform.
  SolutionPoint constant;
  ASSERT_TRUE(locateHit(square.solution, hit, {0, 1, 0}, constant, Reconstruction::Constant));
  applySurfaceDetail(square.solution, square.scene.materials[0], rho, constant);
  EXPECT_NEAR(reflectedRadiosity(square.solution, constant)[0], 2.25, 1e-12);
}

// The one-sided solution holds nothing behind a face: seen from below, the
// square is not located, whatever the caller would read there.
TEST(SolutionQuery, TheBackOfAFaceIsNotInTheSolution) {
  OneElement square(Bands(2.0), Bands(0.0), Bands(0.5), false);
  SolutionPoint at;
  EXPECT_TRUE(locateHit(square.solution, square.hitFrom(1), {0, 1, 0}, at));
  EXPECT_FALSE(locateHit(square.solution, square.hitFrom(-1), {0, -1, 0}, at));
  // Grazing: wo in the plane is not the front either.
  EXPECT_FALSE(locateHit(square.solution, square.hitFrom(1), {1, 0, 0}, at));
}

// One clamping rule: a reflected radiosity below zero (B < E after
// interpolation or a subtraction) reads as 0, so B reads as E; an unscaled
// B ≥ E reads back exactly, with no round trip through B − E.
TEST(SolutionQuery, ReflectedLightIsNeverNegativeAndBReadsBackExactly) {
  OneElement below(Bands(0.3, 0.7, 0.5), Bands(0.5), Bands(0.5), false);
  SolutionPoint at;
  ASSERT_TRUE(locateHit(below.solution, below.hitFrom(1), {0, 1, 0}, at));
  const Bands reflected = reflectedRadiosity(below.solution, at);
  EXPECT_EQ(reflected[0], 0.0);
  EXPECT_NEAR(reflected[1], 0.2, 1e-12);
  const Bands b = radiosity(below.solution, at);
  EXPECT_EQ(b[0], 0.5);
  EXPECT_EQ(b[1], below.solution.interpolatedRadiosity(at.location)[1]);
  EXPECT_EQ(b[2], below.solution.interpolatedRadiosity(at.location)[2]);
  EXPECT_EQ(reflectedRadiosity(below.solution, 0)[0], 0.0);  // the element's own reading too
  // And through a texture factor.
  OneElement textured(Bands(0.3), Bands(0.5), Bands(0.5), true);
  ASSERT_TRUE(locateHit(textured.solution, textured.hitFrom(1), {0, 1, 0}, at));
  applySurfaceDetail(textured.solution, textured.scene.materials[0], Bands(0.9), at);
  EXPECT_EQ(reflectedRadiosity(textured.solution, at).max(), 0.0);
  EXPECT_EQ(radiosity(textured.solution, at)[0], 0.5);
}

// The fields Shirley's method splits the reflected light into: at every node,
// E + direct + indirect is B (a Gauss–Seidel solution, no ambient term).
TEST(SolutionQuery, DirectAndIndirectFieldsAddUpToTheReflectedRadiosity) {
  const int walls[6] = {1, 1, 1, 0, 1, 1};
  Scene scene = test::closedBox(1.0, walls);
  Material light, wall;
  light.name = "light", light.emission = Bands(kInvPi), light.diffuse = Bands(0.0);
  wall.name = "wall", wall.diffuse = Bands(0.5, 0.6, 0.7);
  scene.materials = {light, wall};
  RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.25;
  SolverOptions options;
  options.solver = "gauss-seidel";
  const Solution s = meshAndSolve(scene, tracer, mesh, options);
  const std::vector<Bands> direct = nodeField(s, Field::Direct), indirect = nodeField(s, Field::Indirect);
  const std::vector<Bands> emission = s.nodeValues(s.emission);
  ASSERT_EQ(direct.size(), s.mesh.nodes.size());
  double largestIndirect = 0;
  for (size_t v = 0; v < s.mesh.nodes.size(); ++v) {
    largestIndirect = std::max(largestIndirect, indirect[v].max());
    for (int b = 0; b < kBandCount; ++b)
      EXPECT_NEAR(emission[v][b] + direct[v][b] + indirect[v][b], s.nodeRadiosity[v][b], 1e-9) << v;
  }
  EXPECT_GT(largestIndirect, 0.01);  // the split is not trivial
}

// A leaf receives through its own links and its ancestors' (push–pull): the
// links forEachLinkLighting visits are exactly those whose receiver's subtree
// holds the leaf, found here by walking down from each receiver instead.
TEST(SolutionQuery, TheLinksLightingALeafAreThoseOfItsAncestors) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.15;
  SolverOptions options;
  options.solver = "gauss-seidel";
  EXPECT_FALSE(isHierarchical(meshAndSolve(scene, tracer, mesh, options)));
  options.solver = "hierarchical";
  options.maxElements = 600;
  const Solution s = meshAndSolve(scene, tracer, mesh, options);
  ASSERT_TRUE(isHierarchical(s));
  const LinksByReceiver index = indexLinksByReceiver(s);
  std::vector<std::set<int32_t>> leavesUnder(s.mesh.tree.size());
  auto collect = [&](uint32_t node) {
    std::vector<uint32_t> stack{node};
    while (!stack.empty()) {
      const MeshTreeNode &n = s.mesh.tree[stack.back()];
      stack.pop_back();
      if (n.isLeaf()) leavesUnder[node].insert(n.element);
      for (int32_t c : n.children)
        if (c >= 0) stack.push_back(uint32_t(c));
    }
  };
  size_t checked = 0, visitedInAll = 0;
  for (uint32_t e = 0; e < s.elementCount(); e += 7) {
    std::multiset<const Link *> expected, visited;
    for (const Link &link : s.links) {
      if (leavesUnder[link.receiver].empty()) collect(link.receiver);
      if (leavesUnder[link.receiver].count(int32_t(e))) expected.insert(&link);
    }
    forEachLinkLighting(s, index, e, [&](const Link &link) { visited.insert(&link); });
    EXPECT_EQ(visited, expected) << "element " << e;
    visitedInAll += visited.size(), ++checked;
  }
  EXPECT_GT(checked, 10u);
  EXPECT_GT(visitedInAll, checked);  // leaves are lit through several links
  // A filter keeps only what it accepts.
  const LinksByReceiver partial =
      indexLinksByReceiver(s, [](const Link &link) { return link.visibility == LinkVisibility::Partial; });
  for (const std::vector<uint32_t> &links : partial.links)
    for (uint32_t l : links) EXPECT_EQ(s.links[l].visibility, LinkVisibility::Partial);
}

// F × V against the exact factor: a square 1 m above a point, unoccluded,
// gives F; with an opaque square half-way blocking the middle, the centroid
// ray is blocked (0) and a 3 × 3 grid sees the fraction of its points left. A source that
// straddles the receiver's plane counts its front part only.
TEST(SolutionQuery, VisibleFormFactorIsTheExactFactorTimesTheVisibleFraction) {
  // Quad 0: the source at y = 1 facing down; quad 1: the blocker at y = 0.5 facing down, ±0.1 around x = z = 0.
  const double k = 0.1;
  auto quads = [&](bool blocker) {
    Scene scene;
    scene.objects.push_back({"quads", "test"});
    Material m;
    m.name = "grey", m.diffuse = Bands(0.5);
    scene.materials.push_back(m);
    scene.positions = {{-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5},
                       {-k, 0.5, -k},   {k, 0.5, -k},   {k, 0.5, k},   {-k, 0.5, k}};
    if (blocker)
      test::addQuads(scene, {0, 0});
    else
      test::addQuads(scene, {0});
    return scene;
  };
  const Scene scene = quads(true), open = quads(false);
  const std::vector<Vec3> source(scene.positions.begin(), scene.positions.begin() + 4);
  const Vec3 p{0, 0, 0}, n{0, 1, 0}, down{0, -1, 0};
  const double exact = formFactorPointToPolygon(p, n, source);
  RayTracer openTracer(open), tracer(scene);
  VisibilitySamples centroid, grid;
  centroid.centroid = true;
  grid.grid = 3;
  EXPECT_EQ(visibleFormFactor(openTracer, p, n, n, source, down, grid), exact);
  EXPECT_EQ(visibleFormFactor(tracer, p, n, n, source, down, centroid), 0.0);
  // The grid's points are sampleConvexPolygon's images of the cells' centres;
  // a ray to one is blocked where it crosses y = ½ inside the blocker.
  int visible = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const Vec3 y = sampleConvexPolygon(source, (a + 0.5) / 3, (b + 0.5) / 3);
      visible += std::abs(y.x / 2) >= k || std::abs(y.z / 2) >= k;
    }
  ASSERT_GT(visible, 0);
  ASSERT_LT(visible, 9);
  EXPECT_NEAR(visibleFormFactor(tracer, p, n, n, source, down, grid), exact * visible / 9, 1e-15);
  // A receiver tilted so that only x < 0.2 of the source is in front of it:
  // the factor of that part, its centroid (x = −0.15) visible in the open scene.
  const Vec3 tilted = normalize(Vec3{-1, 0.2, 0});
  std::vector<Vec3> front;
  clipToFrontHalfSpace(p, tilted, source, front);
  ASSERT_EQ(front.size(), 4u);
  const double frontFactor = formFactorPointToPolygon(p, tilted, front);
  EXPECT_GT(frontFactor, 0.0);
  EXPECT_NEAR(visibleFormFactor(openTracer, p, tilted, n, source, down, centroid), frontFactor, 1e-15);
}

}  // namespace
}  // namespace radiant
