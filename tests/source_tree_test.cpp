// reichert's gather through a cut of the elements' tree (render/source_tree.h):
// in a closed cube nothing occludes, so the sum over every element of
// B_j F(dx → A_j), F by Lambert's contour integral, is exact; the cut's
// estimate must equal it in expectation, whatever the cut, and the sum with
// cut-error 0 must be it.
#include "render/source_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "mesh/mesh.h"
#include "radiosity/form_factor.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "render_helpers.h"
#include "scene/camera.h"
#include "scene/load_scene.h"
#include "scene/scene.h"
#include "test_scenes.h"

namespace radiant {
namespace {

/// The unit cube lit by its ceiling (E = 1), the other faces ρ = 0.5, meshed
/// into 20 × 20 elements a face, each given a radiosity that varies across
/// the walls (a made-up field: the test is of the gather, not the solve).
struct MeshedCube {
  Scene scene = test::unitCubeWithCeilingLight();
  RayTracer tracer{scene};
  Solution solution = [this] {
    MeshOptions meshOptions;
    meshOptions.maxEdgeLength = 0.05;
    Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
    for (uint32_t e = 0; e < s.elementCount(); ++e) {
      const Vec3 c = s.mesh.elements[e].centre;
      if (s.mesh.normalOf(e).y > -0.5) s.radiosity[e] = Bands(0.05 + 0.3 * c.x * c.x + 0.2 * c.z + 0.1 * c.y);
    }
    s.updateNodesAndErrors();
    return s;
  }();
};

/// Σ_j B_j F(x → A_j): nothing occludes inside the cube.
double exactIrradiance(const Solution &solution, const Vec3 &x, const Vec3 &n) {
  double sum = 0;
  for (uint32_t e = 0; e < solution.elementCount(); ++e) {
    const std::vector<Vec3> polygon = solution.mesh.polygon(e);
    if (dot(x - solution.mesh.elements[e].centre, solution.mesh.normalOf(e)) <= 0) continue;
    sum += solution.displayRadiosity(e)[0] * formFactorPointToPolygon(x, n, polygon);
  }
  return sum;
}

TEST(SourceTree, EveryElementIsALeafAndTheCutOfZeroErrorHoldsEveryOneInFront) {
  MeshedCube cube;
  SourceTree tree(cube.solution);
  EXPECT_EQ(tree.nodeCount(), 2 * cube.solution.elementCount() - 1);
  std::vector<SourceTree::CutNode> cut;
  const Vec3 x{0.3, 0.0, 0.6}, n{0, 1, 0};
  tree.chooseCut(x, n, 0, 64, cut);
  // Every element x can see is a leaf of the cut (the bounds may keep the
  // floor's own, in x's plane, which then add nothing), each once.
  std::vector<int> inCut(cube.solution.elementCount(), 0);
  for (const SourceTree::CutNode &c : cut) {
    ASSERT_TRUE(c.leaf);
    double p = 0;
    ++inCut[tree.drawElement(c.node, x, n, 0.5, p)];
    EXPECT_EQ(p, 1.0);
  }
  for (uint32_t e = 0; e < cube.solution.elementCount(); ++e) {
    const bool inFront = dot(x - cube.solution.mesh.elements[e].centre, cube.solution.mesh.normalOf(e)) > 0;
    EXPECT_EQ(inCut[e], inFront ? 1 : inCut[e] > 0) << "element " << e;
  }
}

TEST(SourceTree, AnElementIsDrawnWithTheChanceItIsWeightedBy) {
  // Over many draws from the root, each element's frequency matches the
  // probability drawElement reports for it (the weight 1/p is then unbiased).
  MeshedCube cube;
  SourceTree tree(cube.solution);
  std::vector<SourceTree::CutNode> cut;
  const Vec3 x{0.5, 0.0, 0.5}, n{0, 1, 0};
  tree.chooseCut(x, n, 1.0, 1, cut);
  ASSERT_EQ(cut.size(), 1u);
  std::vector<double> probability(cube.solution.elementCount(), -1);
  std::vector<int> count(cube.solution.elementCount(), 0);
  constexpr int kDraws = 400000;
  Pcg32 rng;
  for (int k = 0; k < kDraws; ++k) {
    double p = 0;
    const uint32_t e = tree.drawElement(cut[0].node, x, n, rng.next(), p);
    ++count[e];
    if (probability[e] >= 0) {
      EXPECT_DOUBLE_EQ(probability[e], p);
    }
    probability[e] = p;
  }
  double total = 0;
  int checked = 0;
  for (uint32_t e = 0; e < cube.solution.elementCount(); ++e) {
    if (probability[e] < 0) continue;
    total += probability[e];
    if (probability[e] * kDraws < 200) continue;
    const double sigma = std::sqrt(kDraws * probability[e] * (1 - probability[e]));
    EXPECT_NEAR(count[e], kDraws * probability[e], 5 * sigma) << "element " << e;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_LE(total, 1 + 1e-9);  // the elements never drawn hold the rest
}

TEST(SourceTree, ReichertThroughACutEqualsTheGatherOverEveryElementInExpectation) {
  MeshedCube cube;
  RenderContext context;
  context.solution = &cube.solution;
  const Ray ray{{0.3, 0.9, 0.6}, {0, -1, 0}};  // to the floor at (0.3, 0, 0.6)
  const double exact = 0.5 * kInvPi * exactIrradiance(cube.solution, {0.3, 0, 0.6}, {0, 1, 0});
  for (const char *ff : {"point", "mc"}) {
    // Every element: the exact sum (no occluder, so visibility is 1 wherever it is sampled).
    auto every = createRenderer("reichert", cube.tracer, context,
                                test::parameters({{"ff", ff}, {"cut-error", "0"}, {"gather-chance", "1"}}));
    Sampler one{Pcg32()};
    EXPECT_NEAR(every->radiance(ray, one)[0], exact, 1e-7 * exact) << ff;  // the sums' order aside
  }
  // A cut of at most 8 nodes of 2000 elements: each node read through one
  // element drawn at random and weighted by its chance. The mean of many
  // estimates is the exact sum within 4 standard errors, and that error is
  // small enough (below 0.2 %) to see a bias of 1 %.
  auto cut =
      createRenderer("reichert", cube.tracer, context, test::parameters({{"max-cut", "8"}, {"gather-chance", "1"}}));
  constexpr int kSamples = 20000;
  double sum = 0, sumSquares = 0;
  for (int s = 0; s < kSamples; ++s) {
    Sampler rng(sampleGenerator(11, 0, uint64_t(s)));
    const double v = cut->radiance(ray, rng)[0];
    sum += v, sumSquares += v * v;
  }
  const double mean = sum / kSamples;
  const double standardError = std::sqrt(std::max(0.0, sumSquares / kSamples - mean * mean) / (kSamples - 1));
  EXPECT_NEAR(mean, exact, 4 * standardError);
  EXPECT_LT(standardError, 0.002 * exact);
}

TEST(SourceTree, AGathersWorkDoesNotGrowWithTheElementCount) {
  // Issue 37: reichert's cost a sample follows the cut, not the mesh. The
  // Cornell box meshed at 1× and 16× the elements (the same made-up light
  // field: emission plus ρ × 0.3); at the same points on its walls, floor and
  // blocks, the work of a gather (its cut's nodes, each a form factor and a
  // shadow ray, plus the nodes opened and the levels descended to draw an
  // element) grows by less than 2× (bench/reichert_scaling times it). A
  // descent by importance to every element took 2.1× more work.
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  const RayTracer tracer(scene);
  auto workPerGather = [&](double edge, size_t &elements) {
    MeshOptions options;
    options.maxEdgeLength = edge;
    Solution solution = initialSolution(scene, buildMesh(scene, options));
    elements = solution.elementCount();
    for (size_t e = 0; e < elements; ++e)
      solution.radiosity[e] = solution.emission[e] + solution.reflectance[e] * Bands(0.3);
    const SourceTree tree(solution);
    const PinholeCamera camera(scene.camera, 32, 32);
    SourceTree::Work work;
    std::vector<SourceTree::CutNode> cut;
    long nodes = 0, gathers = 0;
    for (int pixel = 0; pixel < 32 * 32; ++pixel) {
      Hit hit;
      if (!tracer.intersect(camera.generateRay(pixel % 32 + 0.5, pixel / 32 + 0.5), hit)) continue;
      tree.chooseCut(hit.position, hit.shadingNormal, 0.02, 256, cut, &work);
      double probability = 0;
      for (const SourceTree::CutNode &node : cut)
        tree.drawElement(node.node, hit.position, hit.shadingNormal, 0.5, probability, &work);
      nodes += long(cut.size()), ++gathers;
    }
    return double(nodes + work.splits + work.levels) / double(gathers);
  };
  size_t coarse = 0, fine = 0;
  const double coarseWork = workPerGather(0.05, coarse), fineWork = workPerGather(0.0125, fine);
  EXPECT_GT(fine, 12 * coarse);
  EXPECT_LT(fineWork, 2 * coarseWork) << coarse << " elements: " << coarseWork << "; " << fine
                                      << " elements: " << fineWork;
  std::cout << "work per gather: " << coarseWork << " (" << coarse << " elements), " << fineWork << " (" << fine
            << " elements)\n";
}

}  // namespace
}  // namespace radiant
