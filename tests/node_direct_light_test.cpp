// The stochastic solver's direct light at the nodes (radiosity/node_direct_light.h)
// and its reflected light's density estimate (radiosity/reflected_light_density.h).
// Closed forms: Lambert's contour integral for an unoccluded area light
// (the node values must be it to round-off), a fine quadrature of the same
// for the power a floor receives, and synthetic ray deposits whose density
// is known, with tolerances from their Poisson noise.
#include "radiosity/node_direct_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/form_factor.h"
#include "radiosity/reflected_light_density.h"
#include "raytrace/ray_tracer.h"
#include "test_scenes.h"
#include "util/random.h"

namespace radiant {
namespace {

constexpr double kRadiance = 10;                                                                // W·sr⁻¹·m⁻²
const std::vector<Vec3> kLight = {{0.4, 1, 0.4}, {0.6, 1, 0.4}, {0.6, 1, 0.6}, {0.4, 1, 0.6}};  // facing −y

/// A 1 m² floor (face 0, facing up, ρ = 0.5) under a 0.2 m square light 1 m above it (face 1).
Scene floorUnderALight() {
  Scene s;
  s.objects.push_back({"test", "test"});
  Material floor;
  floor.diffuse = Bands(0.5);
  Material light;
  light.diffuse = Bands(0.0);
  light.emission = Bands(kRadiance);
  s.materials = {floor, light};
  test::addQuad(s, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, 0);
  test::addQuad(s, {kLight[0], kLight[1], kLight[2], kLight[3]}, 1);
  return s;
}

double irradianceUnderTheLight(const Vec3 &x) {
  return kPi * kRadiance * formFactorPointToPolygon(x, Vec3{0, 1, 0}, kLight);
}

TEST(NodeDirectLight, AtEveryNodeItIsTheLightsExitanceTimesTheFormFactor) {
  const Scene scene = floorUnderALight();
  const RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.1;
  const Solution s = initialSolution(scene, buildMesh(scene, mesh));
  const MeshDirectLight light = directLightOfMesh(tracer, s, 0);
  ASSERT_EQ(light.atNodes.size(), s.mesh.nodes.size());
  size_t checked = 0;
  for (uint32_t v = 0; v < s.mesh.nodes.size(); ++v) {
    if (s.mesh.patches[s.mesh.nodePatch[v]].face != 0) continue;
    // Evaluated 10⁻⁷ of the way to the patch's centre: a relative change of that order.
    EXPECT_NEAR(light.atNodes[v][0] / irradianceUnderTheLight(s.mesh.nodes[v]), 1.0, 1e-6) << "node " << v;
    ++checked;
  }
  EXPECT_EQ(checked, 121u);  // 11 × 11 nodes
}

TEST(NodeDirectLight, TheElementsMeansCarryThePowerThatArrives) {
  // Σ H̄_e A_e over the floor against a 400 × 400 midpoint rule of the exact
  // irradiance (its own error below 10⁻⁵ for a light 1 m away). The elements'
  // 3 × 3 rule errs by about (h/3)²/24 · H''/H, 10⁻⁴ here; the corners' mean
  // (trapezoid rule) of a point light's 1/d² over a large element is the
  // kind of error this catches (it was 1.2 % in a point-lit room).
  const Scene scene = floorUnderALight();
  const RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.1;
  const Solution s = initialSolution(scene, buildMesh(scene, mesh));
  const MeshDirectLight light = directLightOfMesh(tracer, s, 0);
  double power = 0;
  for (uint32_t e = 0; e < s.elementCount(); ++e)
    if (s.mesh.patchOf(e).face == 0) power += light.ofElements[e][0] * s.mesh.elements[e].area;
  constexpr int kGrid = 400;
  double reference = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j)
      reference += irradianceUnderTheLight(Vec3{(i + 0.5) / kGrid, 0, (j + 0.5) / kGrid}) / (kGrid * kGrid);
  EXPECT_NEAR(power / reference, 1.0, 1e-3);
}

/// A scene of grey quads (ρ = 0.5), all of one object and material.
Scene greyQuads(std::initializer_list<std::initializer_list<Vec3>> quads) {
  Scene scene;
  scene.objects.push_back({"test", "test"});
  Material m;
  m.diffuse = Bands(0.5);
  scene.materials = {m};
  for (const auto &corners : quads) test::addQuad(scene, corners, 0);
  return scene;
}

/// A 1 m² floor meshed into 100 × 100 elements (object 0, facing up) and,
/// with `panel`, a panel's underside 1 mm above it (facing down, same object).
Solution finelyMeshedFloor(bool panel) {
  Scene scene = greyQuads({{{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}});
  if (panel) test::addQuad(scene, {{0, 0.001, 0}, {1, 0.001, 0}, {1, 0.001, 1}, {0, 0.001, 1}}, 0);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.01;
  return initialSolution(scene, buildMesh(scene, mesh));
}

/// What landed on each element: power (W) and the rays that brought it.
struct Deposits {
  std::vector<Bands> power;
  std::vector<double> rays;
  explicit Deposits(const Solution &s) : power(s.elementCount(), Bands(0.0)), rays(s.elementCount(), 0.0) {}

  /// Deposits of density `density` (W·m⁻²) on the elements facing
  /// `normalY`: a Poisson number of rays of mean `meanRays` each, every ray
  /// carrying density·A/meanRays.
  void add(const Solution &s, double normalY, double density, double meanRays, Pcg32 &rng) {
    for (uint32_t e = 0; e < s.elementCount(); ++e) {
      if (s.mesh.normalOf(e).y * normalY <= 0) continue;
      // Poisson by inversion (the mean is small).
      int k = 0;
      for (double p = std::exp(-meanRays), cdf = p, u = rng.next(); u > cdf && k < 1000; cdf += p) p *= meanRays / ++k;
      rays[e] = k;
      power[e] = Bands(k * density * s.mesh.elements[e].area / meanRays);
    }
  }
  /// Their irradiance per element (W·m⁻²).
  std::vector<Bands> irradiance(const Solution &s) const {
    std::vector<Bands> h(s.elementCount());
    for (uint32_t e = 0; e < s.elementCount(); ++e) h[e] = power[e] / s.mesh.elements[e].area;
    return h;
  }
};

TEST(ReflectedLightDensity, SparseRaysArePooledUntilTheirNoiseIsSmall) {
  // 4 rays per element on average: a node's own 4 elements hold about 16
  // (25 % noise). The estimate pools at least 400 (≤ 5 %), so the RMS
  // relative deviation over the nodes stays below 8 %, and the mean is the
  // density (the pooling is a weighted average of unbiased estimates).
  const Solution s = finelyMeshedFloor(false);
  Deposits d(s);
  Pcg32 rng(7, 3);
  d.add(s, 1, 2.0, 4.0, rng);
  const std::vector<Bands> h = reflectedIrradianceAtNodes(s, d.power, d.rays, 400, 0);
  const std::vector<Bands> plain = s.nodeValues(d.irradiance(s));
  double sum = 0, squares = 0, rawSquares = 0;
  for (size_t v = 0; v < h.size(); ++v) {
    sum += h[v][0];
    squares += (h[v][0] / 2.0 - 1) * (h[v][0] / 2.0 - 1);
    rawSquares += (plain[v][0] / 2.0 - 1) * (plain[v][0] / 2.0 - 1);
  }
  const double n = double(h.size());
  EXPECT_NEAR(sum / n / 2.0, 1.0, 0.02);
  EXPECT_LT(std::sqrt(squares / n), 0.08);
  EXPECT_GT(std::sqrt(rawSquares / n), 0.15) << "the unpooled node values are this noisy";
}

TEST(ReflectedLightDensity, NodesWithEnoughRaysKeepTheirElementsMean) {
  const Solution s = finelyMeshedFloor(false);
  Deposits d(s);
  Pcg32 rng(11, 5);
  d.add(s, 1, 2.0, 400.0, rng);
  const std::vector<Bands> h = reflectedIrradianceAtNodes(s, d.power, d.rays, 400, 0);
  const std::vector<Bands> plain = s.nodeValues(d.irradiance(s));
  size_t kept = 0;
  for (size_t v = 0; v < h.size(); ++v)
    if (std::abs(h[v][0] / plain[v][0] - 1) < 1e-12) ++kept;
  // Every node but those of a corner (one element, about 400 rays: some below).
  EXPECT_GT(kept, h.size() - 8);
}

TEST(ReflectedLightDensity, SurfacesFacingAwayFromEachOtherAreNeverPooled) {
  // A floor (density 2) and a panel's underside 1 mm above it (density 6),
  // one object: pooled together they would both read about 4.
  const Solution s = finelyMeshedFloor(true);
  Deposits d(s);
  Pcg32 rng(13, 9);
  d.add(s, 1, 2.0, 4.0, rng);
  d.add(s, -1, 6.0, 4.0, rng);
  const std::vector<Bands> h = reflectedIrradianceAtNodes(s, d.power, d.rays, 400, 0);
  double floor = 0, panel = 0;
  size_t floorNodes = 0, panelNodes = 0;
  for (uint32_t v = 0; v < h.size(); ++v) {
    const bool up = s.mesh.patches[s.mesh.nodePatch[v]].normal.y > 0;
    (up ? floor : panel) += h[v][0];
    ++(up ? floorNodes : panelNodes);
  }
  EXPECT_NEAR(floor / double(floorNodes), 2.0, 0.04);
  EXPECT_NEAR(panel / double(panelNodes), 6.0, 0.12);
}

// The pools are kept for the mesh they were found on (Solution::nodePools):
// a changed mesh, even in a copy that shares them, gets its own.
TEST(NodePools, AreFoundAgainWhenTheMeshChanges) {
  const Scene scene =
      greyQuads({{{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, {{1, 0, 0}, {1, 0, 1}, {2, 0, 1}, {2, 0, 0}}});
  MeshOptions options;
  options.maxEdgeLength = 0.5;
  const Solution s = initialSolution(scene, buildMesh(scene, options));
  auto pooled = [](const std::vector<uint32_t> &pools) {
    size_t count = 0;
    for (uint32_t v = 0; v < pools.size(); ++v) count += pools[v] != v;
    return count;
  };
  const std::vector<uint32_t> before = s.nodePools();
  EXPECT_EQ(pooled(before), 3u);  // the shared edge's three nodes
  Solution moved = s;
  for (uint32_t v = 0; v < moved.mesh.nodes.size(); ++v)
    if (moved.mesh.patches[moved.mesh.nodePatch[v]].face == 1) moved.mesh.nodes[v].x += 0.25;
  EXPECT_EQ(pooled(moved.nodePools()), 0u);
  EXPECT_EQ(s.nodePools(), before);
  EXPECT_EQ(pooled(moved.nodePools()), 0u);
}

}  // namespace
}  // namespace radiant
