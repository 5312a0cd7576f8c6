// The stochastic solver's mesh refined to the direct light
// (radiosity/direct_light_mesh.h): a block standing on a floor under a
// square light, whose contact shadow a uniform mesh of the default element
// size smears. The reference is the exact direct irradiance
// (backprojection, radiosity/backprojection.h) at every point of a fine
// grid, against which the display's interpolation of the node values is
// measured.
#include "radiosity/direct_light_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "radiosity/backprojection.h"
#include "radiosity/node_direct_light.h"
#include "test_scenes.h"

namespace radiant {
namespace {

constexpr double kLo = 0.45, kHi = 0.55, kHeight = 0.1;  // the block, metres
constexpr double kElement = 1.0 / 32;                    // the stochastic solver's walls: 1/32 of the scene

/// A 1 m² floor (face 0, ρ = 0.5) with a 0.1 m block on it (faces 1–5),
/// under a 0.2 m square light 1 m up (face 6, 10 W·sr⁻¹·m⁻²).
Scene blockOnAFloor() {
  Scene s;
  s.objects.push_back({"test", "test"});
  Material grey;
  grey.diffuse = Bands(0.5);
  Material light;
  light.diffuse = Bands(0.0);
  light.emission = Bands(10.0);
  s.materials = {grey, light};
  test::addQuad(s, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, 0);
  const double lo = kLo, hi = kHi, h = kHeight;
  test::addQuad(s, {{lo, 0, lo}, {lo, 0, hi}, {lo, h, hi}, {lo, h, lo}}, 0);  // −x
  test::addQuad(s, {{hi, 0, lo}, {hi, h, lo}, {hi, h, hi}, {hi, 0, hi}}, 0);  // +x
  test::addQuad(s, {{lo, 0, lo}, {lo, h, lo}, {hi, h, lo}, {hi, 0, lo}}, 0);  // −z
  test::addQuad(s, {{lo, 0, hi}, {hi, 0, hi}, {hi, h, hi}, {lo, h, hi}}, 0);  // +z
  test::addQuad(s, {{lo, h, lo}, {lo, h, hi}, {hi, h, hi}, {hi, h, lo}}, 0);  // top
  test::addQuad(s, {{0.4, 1, 0.4}, {0.6, 1, 0.4}, {0.6, 1, 0.6}, {0.4, 1, 0.6}}, 1);
  return s;
}

/// The display's error in the direct light on the floor within `band` of
/// the block (its footprint left out): mean |H_interpolated − H_exact| over
/// a 1 mm grid, relative to the floor's mean exact irradiance.
double contactError(const Scene &scene, const RayTracer &tracer, const Solution &s, double band) {
  const MeshDirectLight light = directLightOfMesh(tracer, s, 0);
  const DirectIrradiance exact(scene, tracer, 48);
  constexpr int kGrid = 1000;
  double error = 0, total = 0;
  size_t inBand = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec3 x{(i + 0.5) / kGrid, 0, (j + 0.5) / kGrid};
      const double reference = exact.irradiance(x + Vec3{0, 1e-9, 0}, Vec3{0, 1, 0})[0];
      total += reference;
      const bool near = x.x > kLo - band && x.x < kHi + band && x.z > kLo - band && x.z < kHi + band;
      const bool under = x.x > kLo && x.x < kHi && x.z > kLo && x.z < kHi;
      if (!near || under) continue;
      error += std::abs(s.interpolate(light.atNodes, s.mesh.locate(0, x))[0] - reference);
      ++inBand;
    }
  return (error / double(inBand)) / (total / double(kGrid * kGrid));
}

TEST(DirectLightMesh, TheContactShadowIsInTheMesh) {
  // Each leaf passes the interpolation test at its edge midpoints and centre
  // to the tolerance, 0.5 % of the mean first-bounce radiosity (ρ the same
  // everywhere here, so 0.5 % of the mean irradiance of the floor and the
  // block), which bounds the error over a leaf to about that where the light
  // varies smoothly across it. Leaves at the smallest size (1/256 m) may keep
  // more along the shadow's edges, which run through the 2 cm band measured:
  // allow twice the tolerance in all. A uniform mesh of the default element
  // size (31 mm) spreads the block's contact shadow over the element beside
  // it: about 15 % there (the second assertion keeps the test able to tell).
  const Scene scene = blockOnAFloor();
  const RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = kElement;
  SolverOptions options;
  options.directTolerance = 0.005;
  const DirectLightMesh refined = buildDirectLightMesh(scene, tracer, mesh, options);
  constexpr double kBand = 0.02;
  const double refinedError = contactError(scene, tracer, initialSolution(scene, refined.mesh), kBand);
  const double uniformError = contactError(scene, tracer, initialSolution(scene, buildMesh(scene, mesh)), kBand);
  EXPECT_LT(refinedError, 2 * options.directTolerance);
  EXPECT_GT(uniformError, 5 * options.directTolerance);
}

TEST(DirectLightMesh, TheValuesItKnowsAreTheSolversOwn) {
  // The stochastic solver reads the nodes' and elements' direct light the
  // refinement evaluated instead of evaluating it again: the same
  // backprojection at the same point with the same normal for the nodes;
  // Simpson's rule over each leaf's tested points for the elements, whose
  // power over the floor must agree with the solver's own lattice means to
  // within the refinement's tolerance.
  const Scene scene = blockOnAFloor();
  const RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = kElement;
  SolverOptions options;
  DirectLightMesh refined = buildDirectLightMesh(scene, tracer, mesh, options);
  Solution known = initialSolution(scene, refined.mesh);
  known.knownNodeDirect = refined.nodeDirect, known.knownElementDirect = refined.elementDirect;
  const Solution fresh = initialSolution(scene, refined.mesh);
  const MeshDirectLight reused = directLightOfMesh(tracer, known, 0), evaluated = directLightOfMesh(tracer, fresh, 0);
  size_t knownNodes = 0;
  for (uint32_t v = 0; v < known.mesh.nodes.size(); ++v) {
    if (std::isnan(refined.nodeDirect[v][0])) continue;
    ++knownNodes;
    EXPECT_NEAR(reused.atNodes[v][0], evaluated.atNodes[v][0], 1e-9 * (1 + evaluated.atNodes[v][0])) << "node " << v;
  }
  EXPECT_GT(knownNodes, known.mesh.nodes.size() / 2);
  double reusedPower = 0, evaluatedPower = 0;
  for (uint32_t e = 0; e < known.elementCount(); ++e)
    if (known.mesh.patchOf(e).face == 0) {
      reusedPower += reused.ofElements[e][0] * known.mesh.elements[e].area;
      evaluatedPower += evaluated.ofElements[e][0] * known.mesh.elements[e].area;
    }
  EXPECT_NEAR(reusedPower / evaluatedPower, 1.0, 0.005);
}

TEST(DirectLightMesh, AModelsFacetsAreNotRefined) {
  // A floor of 32 × 32 quads of the element size: each is one element, too
  // small to be refined (a tessellated model's facets), however its light varies.
  Scene scene = blockOnAFloor();
  Scene tiled;
  tiled.objects = scene.objects;
  tiled.materials = scene.materials;
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) {
      const double x0 = i * kElement, z0 = j * kElement, x1 = x0 + kElement, z1 = z0 + kElement;
      test::addQuad(tiled, {{x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}}, 0);
    }
  test::addQuad(tiled, {{0.4, 1, 0.4}, {0.6, 1, 0.4}, {0.6, 1, 0.6}, {0.4, 1, 0.6}}, 1);
  const RayTracer tracer(tiled);
  MeshOptions mesh;
  mesh.maxEdgeLength = kElement;
  const DirectLightMesh refined = buildDirectLightMesh(tiled, tracer, mesh, SolverOptions{});
  EXPECT_EQ(refined.mesh.elements.size(), buildTreeMesh(tiled, mesh).elements.size());
  EXPECT_TRUE(refined.nodeDirect.empty());
}

TEST(DirectLightMesh, EveryPointIsLocatedInItsElementByTheCompactDescent) {
  // locateInTree descends RadiosityMesh::treeDescent, the children alone,
  // from the patch's shortcut grid (RadiosityMesh::TreeShortcut), while they
  // match the tree; the refined floor has leaves from 1/32 down to 1/256 m.
  // Points inside each leaf (a fixed blend of its corners) must be found in
  // it, and at the same (s, t) as by descending the full nodes from the root.
  const Scene scene = blockOnAFloor();
  const RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = kElement;
  RadiosityMesh mesh = buildDirectLightMesh(scene, tracer, meshOptions, SolverOptions{}).mesh;
  ASSERT_EQ(mesh.treeDescent.size(), mesh.tree.size());
  const uint32_t floorPatch = uint32_t(mesh.patchOfFace[0]);
  ASSERT_GE(mesh.treeShortcutOfPatch.at(floorPatch).level, 3);  // the floor's tree is 5 levels deep
  RadiosityMesh slow = mesh;
  slow.treeDescent.clear();
  size_t checked = 0;
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const std::vector<Vec3> polygon = mesh.polygon(e);
    const double w[4] = {0.4, 0.3, 0.2, 0.1};
    Vec3 x;
    for (size_t k = 0; k < polygon.size(); ++k) x += polygon[k] * (polygon.size() == 4 ? w[k] : 1.0 / 3);
    const uint32_t face = mesh.patches[mesh.elements[e].patch].face;
    const MeshLocation fast = mesh.locate(face, x), full = slow.locate(face, x);
    EXPECT_EQ(fast.element, e);
    EXPECT_EQ(fast.element, full.element);
    EXPECT_EQ(fast.s, full.s);
    EXPECT_EQ(fast.t, full.t);
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
  // On the floor's lines of the shortcut grid and of every level below it,
  // where a step of either descent could round the other way: the corners
  // and edge midpoints of its leaves, its own corners and points just
  // outside it (clamped).
  size_t onLines = 0;
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    if (mesh.elements[e].patch != floorPatch) continue;
    const std::vector<Vec3> polygon = mesh.polygon(e);
    for (size_t k = 0; k < polygon.size(); ++k)
      for (const Vec3 &x : {polygon[k], (polygon[k] + polygon[(k + 1) % polygon.size()]) * 0.5}) {
        const MeshLocation fast = mesh.locate(0, x), full = slow.locate(0, x);
        EXPECT_EQ(fast.element, full.element);
        EXPECT_EQ(fast.s, full.s);
        EXPECT_EQ(fast.t, full.t);
        ++onLines;
      }
  }
  EXPECT_GT(onLines, 4000u);
  for (const Vec3 &x : {Vec3{-0.01, 0, -0.01}, Vec3{1.01, 0, 0.5}, Vec3{0.5, 0, 1.01}, Vec3{1, 0, 1}}) {
    const MeshLocation fast = mesh.locate(0, x), full = slow.locate(0, x);
    EXPECT_EQ(fast.element, full.element);
    EXPECT_EQ(fast.s, full.s);
    EXPECT_EQ(fast.t, full.t);
  }
}

TEST(DirectLightMesh, AWholeFacetIsItsOwnElementWithoutLocating) {
  // wholeFaceElements: the block's faces are smaller than four elements, so
  // they stay one leaf each (a one-node tree); the floor is refined. What a
  // ray's hit on each face reads is the element locate() finds there.
  const Scene scene = blockOnAFloor();
  const RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = kElement * 4;
  const RadiosityMesh mesh = buildDirectLightMesh(scene, tracer, meshOptions, SolverOptions{}).mesh;
  const std::vector<int32_t> whole = mesh.wholeFaceElements();
  ASSERT_EQ(whole.size(), scene.faces.size());
  EXPECT_EQ(whole[0], RadiosityMesh::kLocateElement);  // the floor: a tree of many leaves
  size_t facets = 0;
  for (uint32_t f = 1; f <= 5; ++f) {
    if (whole[f] < 0) continue;
    ++facets;
    Vec3 centre;
    for (int k = 0; k < 4; ++k) centre += scene.positions[scene.faces[f].vertices[k]] * 0.25;
    EXPECT_EQ(uint32_t(whole[f]), mesh.locate(f, centre).element);
  }
  EXPECT_EQ(facets, 5u);
}

}  // namespace
}  // namespace radiant
