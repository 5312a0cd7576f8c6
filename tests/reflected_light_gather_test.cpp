// The stochastic solver's final gather at the nodes (radiosity/reflected_light_gather.h).
// Closed form: a node under a square that leaves radiosity B − E receives
// (B − E)·F(node → square) by Lambert's contour integral; the tolerances
// follow from the gather's noise, bounded by that of independent rays (a
// Bernoulli variable of mean F per ray: stratified rays never do worse).
#include "radiosity/reflected_light_gather.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mesh/mesh.h"
#include "radiosity/form_factor.h"
#include "raytrace/ray_tracer.h"
#include "test_scenes.h"

namespace radiant {
namespace {

constexpr double kCeilingRadiosity = 3, kCeilingEmission = 1;  // W·m⁻²: it reflects 2
const std::vector<Vec3> kCeiling = {{-0.5, 1, -0.5}, {1.5, 1, -0.5}, {1.5, 1, 1.5}, {-0.5, 1, 1.5}};  // facing −y

/// A floor of `side` metres at the origin (face 0, facing up) under a 2 m
/// square 1 m above it (face 1), meshed at `edge`; the ceiling's elements
/// leave kCeilingRadiosity, of which kCeilingEmission is emitted.
Solution floorUnderACeiling(double side, double edge, Scene &scene) {
  scene.objects.push_back({"test", "test"});
  scene.materials.resize(1);
  scene.materials[0].diffuse = Bands(0.5);
  test::addQuad(scene, {{0, 0, 0}, {0, 0, side}, {side, 0, side}, {side, 0, 0}}, 0);
  test::addQuad(scene, {kCeiling[0], kCeiling[1], kCeiling[2], kCeiling[3]}, 0);
  MeshOptions mesh;
  mesh.maxEdgeLength = edge;
  Solution s = initialSolution(scene, buildMesh(scene, mesh));
  for (uint32_t e = 0; e < s.elementCount(); ++e) {
    const bool ceiling = s.mesh.patchOf(e).face == 1;
    s.radiosity[e] = Bands(ceiling ? kCeilingRadiosity : 0.0);
    s.emission[e] = Bands(ceiling ? kCeilingEmission : 0.0);
  }
  return s;
}

std::vector<uint32_t> floorNodes(const Solution &s) {
  std::vector<uint32_t> nodes;
  for (uint32_t v = 0; v < s.mesh.nodes.size(); ++v)
    if (s.mesh.patches[s.mesh.nodePatch[v]].face == 0) nodes.push_back(v);
  return nodes;
}

double exactGather(const Vec3 &x) {
  return (kCeilingRadiosity - kCeilingEmission) * formFactorPointToPolygon(x, Vec3{0, 1, 0}, kCeiling);
}

/// The standard deviation of one node's gather of N independent rays, each
/// reading B − E with probability F and 0 otherwise.
double gatherSigma(double exact, int rays) {
  const double reflected = kCeilingRadiosity - kCeilingEmission, f = exact / reflected;
  return reflected * std::sqrt(f * (1 - f) / rays);
}

TEST(ReflectedLightGather, IsTheReflectedRadiosityTimesTheFormFactor) {
  // Nodes 0.25 m apart: none within the smoothing radius of another, so each is its own gather.
  Scene scene;
  const Solution s = floorUnderACeiling(1.0, 0.25, scene);
  const RayTracer tracer(scene);
  const std::vector<uint32_t> nodes = floorNodes(s);
  ASSERT_EQ(nodes.size(), 25u);
  constexpr int kRays = 1024;
  const std::vector<Bands> gathered = gatherReflectedIrradiance(tracer, s, nodes, kRays, 2.0 / 256, 1, 0);
  double sumDifference = 0, sumVariance = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const double exact = exactGather(s.mesh.nodes[nodes[i]]), sigma = gatherSigma(exact, kRays);
    EXPECT_NEAR(gathered[i][0], exact, 5 * sigma)
        << "node at " << s.mesh.nodes[nodes[i]].x << ", " << s.mesh.nodes[nodes[i]].z;
    EXPECT_EQ(gathered[i][0], gathered[i][2]) << "a grey ceiling gives a grey gather";
    sumDifference += gathered[i][0] - exact;
    sumVariance += sigma * sigma;
  }
  // Over the 25 nodes, a bias would show where single nodes' noise hides it.
  EXPECT_NEAR(sumDifference, 0, 4 * std::sqrt(sumVariance));
}

TEST(ReflectedLightGather, NeighboursPoolTheirNoiseWithoutMovingTheMean) {
  // A 5 cm floor meshed at 2 mm: each node has dozens of others within a
  // smoothing radius of 7.8 mm, over which F changes by under 10⁻³. Pooled,
  // the nodes' RMS error falls to well under half of their own gathers'.
  Scene scene;
  const Solution s = floorUnderACeiling(0.05, 0.002, scene);
  const RayTracer tracer(scene);
  const std::vector<uint32_t> nodes = floorNodes(s);
  constexpr int kRays = 16;
  const std::vector<Bands> own = gatherReflectedIrradiance(tracer, s, nodes, kRays, 0, 3, 0);
  const std::vector<Bands> pooled = gatherReflectedIrradiance(tracer, s, nodes, kRays, 2.0 / 256, 3, 0);
  double ownSquares = 0, pooledSquares = 0, pooledSum = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const double exact = exactGather(s.mesh.nodes[nodes[i]]);
    ownSquares += (own[i][0] - exact) * (own[i][0] - exact);
    pooledSquares += (pooled[i][0] - exact) * (pooled[i][0] - exact);
    pooledSum += pooled[i][0] - exact;
  }
  const double n = double(nodes.size()), sigma = gatherSigma(exactGather({0.025, 0, 0.025}), kRays);
  EXPECT_GT(std::sqrt(ownSquares / n), 0.01 * sigma) << "the nodes' own gathers are noisy";
  EXPECT_LT(std::sqrt(pooledSquares / n), 0.5 * std::sqrt(ownSquares / n));
  // Pooling is a weighted mean of unbiased gathers: their mean error stays within the noise of all of them.
  EXPECT_NEAR(pooledSum / n, 0, 5 * sigma / std::sqrt(n) + 1e-3 * exactGather({0.025, 0, 0.025}));
}

TEST(ReflectedLightGather, IsTheSameWhateverTheThreads) {
  Scene scene;
  const Solution s = floorUnderACeiling(1.0, 0.05, scene);
  const RayTracer tracer(scene);
  const std::vector<uint32_t> nodes = floorNodes(s);
  const std::vector<Bands> one = gatherReflectedIrradiance(tracer, s, nodes, 16, 2.0 / 256, 5, 1);
  const std::vector<Bands> two = gatherReflectedIrradiance(tracer, s, nodes, 16, 2.0 / 256, 5, 2);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) EXPECT_EQ(one[i][1], two[i][1]);
}

}  // namespace
}  // namespace radiant
