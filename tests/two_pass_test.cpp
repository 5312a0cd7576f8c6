// The two-pass methods (C&W §9.3): rushmeier, reichert, shirley, kok and
// selective re-evaluation, against the closed forms of the unit cube lit by
// its ceiling (docs/two-pass.md, `rushmeier`), the furnace (B = E/(1−ρ)) and
// the path tracer.
#include "render/two_pass.h"

#include <gtest/gtest.h>

#include <iostream>

#include "film_metrics.h"
#include "mesh/face_split.h"
#include "radiosity/form_factor.h"
#include "radiosity/solver.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "render/secondary_sources.h"
#include "render_helpers.h"
#include "sanitizer.h"
#include "scene/load_scene.h"
#include "test_scenes.h"

namespace radiant {
namespace {

const char *const kTwoPassMethods[] = {"rushmeier", "reichert", "shirley", "kok"};

/// Mean of many estimates of one camera ray, and the standard error of that mean.
struct Estimate {
  double mean = 0, standardError = 0;
};

Estimate estimateRay(const Renderer &renderer, const Ray &ray, int samples) {
  double sum = 0, sumSquares = 0;
  for (int s = 0; s < samples; ++s) {
    Sampler rng(sampleGenerator(7, 0, uint64_t(s)));
    double v = renderer.radiance(ray, rng)[0];
    sum += v, sumSquares += v * v;
  }
  double mean = sum / samples;
  double variance = std::max(0.0, sumSquares / samples - mean * mean) / (samples - 1);
  return {mean, std::sqrt(variance)};
}

/// The cube's exact patch-level solution (docs/two-pass.md), one element per
/// face: floor 0.1666003, walls 0.1666832, split into direct ρF·E and the rest.
Solution exactCubeSolution(const Scene &scene) {
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 1.0;
  Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
  EXPECT_EQ(s.elementCount(), 6u);
  for (uint32_t e = 0; e < s.elementCount(); ++e) {
    const Vec3 n = s.mesh.normalOf(e);
    if (n.y < -0.5) continue;  // the ceiling: B = E = 1
    const bool floor = n.y > 0.5;
    s.radiosity[e] = Bands(floor ? 0.1666003 : 0.1666832);
    s.direct[e] = Bands(0.5 * (floor ? 0.1998249 : 0.2000438));
    s.indirect[e] = s.radiosity[e] - s.direct[e];
  }
  s.updateNodesAndErrors();
  return s;
}

// Rushmeier's one-bounce gather (C&W eq. 9.10), exact in docs/two-pass.md: at
// the floor centre it is 0.183113 (direct 0.119728 + indirect 0.063385), not
// the element's 0.1666.
constexpr double kGatherAtFloorCentre = 0.183113, kDirectAtFloorCentre = 0.119728;
constexpr double kIndirectAtFloorCentre = 0.063385;
const Ray kRayToFloorCentre{{0.5, 0.5, 0.5}, {0, -1, 0}};
/// The floor element's own indirect radiosity, B − ρF·E (the exact solution
/// above), which shirley interpolates.
constexpr double kIndirectOfTheFloorElement = 0.1666003 - 0.5 * 0.1998249;

/// The unit cube with its exact patch-level solution, and a renderer on it.
struct ExactCube {
  Scene scene = test::unitCubeWithCeilingLight();
  RayTracer tracer{scene};
  Solution solution = exactCubeSolution(scene);
  RenderContext options = [this] {
    RenderContext o;
    o.solution = &solution;
    return o;
  }();
  ParameterValues parameters;
  std::unique_ptr<Renderer> renderer(const std::string &method) const {
    return createRenderer(method, tracer, options, parameters);
  }
};

TEST(TwoPass, RushmeierConvergesToTheGatherAtTheFloorCentre) {
  ExactCube cube;
  Estimate e = estimateRay(*cube.renderer("rushmeier"), kRayToFloorCentre, 400000);
  const double expected = kGatherAtFloorCentre / kPi;  // radiance B/π
  EXPECT_NEAR(e.mean, expected, 4 * e.standardError);
  // …and is told apart from the element average (and from counting the
  // light twice, which would add the direct term again) by many σ.
  EXPECT_GT(std::abs(0.1666003 / kPi - e.mean), 20 * e.standardError);
  std::cout << "rushmeier at the floor centre: " << e.mean * kPi << " ± " << e.standardError * kPi << " (exact "
            << kGatherAtFloorCentre << ")\n";
}

TEST(TwoPass, ReichertGathersTheExactFormFactorsAtTheFloorCentre) {
  // No occluders in the cube: every visibility ray succeeds and the contour
  // integrals make the gather exact, for point and Monte Carlo sampling alike.
  ExactCube cube;
  for (const char *ff : {"point", "mc"}) {
    cube.parameters = test::parameters({{"ff", ff}, {"gather-chance", "1"}});  // the gather alone
    auto renderer = cube.renderer("reichert");
    Sampler rng{Pcg32()};
    EXPECT_NEAR(renderer->radiance(kRayToFloorCentre, rng)[0] * kPi, kGatherAtFloorCentre, 2e-6) << ff;
  }
}

TEST(TwoPass, ReichertsCorrectionOfTheSolutionKeepsTheGathersMeanWhereTheSolutionIsWrong) {
  // Most samples read the solution's interpolated indirect light, a random
  // tenth gather the reflected light and add (gather − solution)/0.1. The
  // floor's solution is made three times too bright; the gather at the floor
  // centre does not read the floor, so its exact value stands, and the mean
  // of the samples must be it. The correcting samples are negative here:
  // clamping them, or leaving them out, would keep the mean near the wrong
  // solution's.
  ExactCube cube;
  for (uint32_t e = 0; e < cube.solution.elementCount(); ++e)
    if (cube.solution.mesh.normalOf(e).y > 0.5) {
      cube.solution.radiosity[e] = Bands(0.5);
      cube.solution.indirect[e] = cube.solution.radiosity[e] - cube.solution.direct[e];
    }
  cube.solution.updateNodesAndErrors();
  cube.parameters = test::parameters({{"gather-chance", "0.1"}});
  auto renderer = cube.renderer("reichert");
  Estimate e = estimateRay(*renderer, kRayToFloorCentre, 40000);
  const double expected = kGatherAtFloorCentre / kPi;
  EXPECT_NEAR(e.mean, expected, 4 * e.standardError);
  EXPECT_LT(e.standardError, 0.05 * expected);  // power: the wrong solution's 0.5/π is far off
  EXPECT_GT(std::abs(0.5 / kPi - e.mean), 20 * e.standardError);
}

TEST(TwoPass, ReichertCountsTheFrontPartOfACutElement) {
  // A small wall at x = 0 facing +x stands on a large emitting floor
  // (x, z in [−1, 1], one element) whose centre lies in the wall's own plane.
  // Only the floor's half with x > 0 lights the wall. Its exact share is
  // F(dx → that half), the clipped contour integral; a visibility point on
  // the other half would be hidden by the wall itself.
  Scene scene;
  scene.objects.push_back({"test", "test"});
  scene.positions = {{-1, 0, -1},   {-1, 0, 1},     {1, 0, 1},      {1, 0, -1},      // floor, facing +y
                     {0, 0.1, 0.1}, {0, 0.1, -0.1}, {0, 0.3, -0.1}, {0, 0.3, 0.1}};  // wall, facing +x
  Material floor, wall;
  floor.name = "floor";
  floor.diffuse = Bands(0.0);
  floor.emission = Bands(kInvPi);  // exitance E = 1
  wall.name = "wall";
  wall.diffuse = Bands(0.5);
  scene.materials = {floor, wall};
  test::addQuads(scene, {0, 1});
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 10;                                             // one element per face
  Solution solution = initialSolution(scene, buildMesh(scene, meshOptions));  // B = E: nothing to solve
  ASSERT_EQ(solution.elementCount(), 2u);
  const Vec3 x{0, 0.2, 0}, n{1, 0, 0};
  const std::vector<Vec3> frontHalf = {{0, 0, -1}, {0, 0, 1}, {1, 0, 1}, {1, 0, -1}};
  const double expected = 0.5 * kInvPi * formFactorPointToPolygon(x, n, frontHalf);
  ASSERT_GT(expected, 0.01);
  for (const char *ff : {"point", "mc"}) {
    RenderContext options;
    options.solution = &solution;
    auto renderer = createRenderer("reichert", tracer, options, test::parameters({{"ff", ff}, {"gather-chance", "1"}}));
    for (int s = 0; s < 16; ++s) {
      Sampler rng(sampleGenerator(5, 0, uint64_t(s)));
      EXPECT_NEAR(renderer->radiance({{1, 0.2, 0}, {-1, 0, 0}}, rng)[0], expected, 1e-9 * expected) << ff;
    }
  }
}

TEST(TwoPass, ShirleyAddsTheInterpolatedIndirectToTheExactDirect) {
  ExactCube cube;
  Estimate e = estimateRay(*cube.renderer("shirley"), kRayToFloorCentre, 100000);
  // The direct term is exact now (backprojection: no noise), so the
  // reference constants' six digits set the tolerance.
  const double expected = (kDirectAtFloorCentre + kIndirectOfTheFloorElement) / kPi;
  EXPECT_NEAR(e.mean, expected, 4 * e.standardError + 5e-6 * expected);
}

TEST(TwoPass, KokRemovesExactlyWhatItSamplesFromTheSecondarySources) {
  // All four walls selected (the ceiling reflects nothing): the removal
  // at the floor element's centre is the exact wall gather there, 0.063385,
  // so sampling the walls per pixel and removing their share from the
  // solution leaves shirley's expectation at that point.
  ExactCube cube;
  const Solution &solution = cube.solution;
  SecondarySourceOptions selection;
  selection.count = 10;
  selection.visibilityGrid = 2;
  SecondarySources sources(cube.tracer, solution, selection);
  EXPECT_EQ(sources.patches().size(), 5u);  // 4 walls and the floor; the ceiling reflects nothing
  EXPECT_NEAR(sources.powerFraction(), 1.0, 1e-12);
  for (uint32_t e = 0; e < solution.elementCount(); ++e) {
    if (solution.mesh.normalOf(e).y > 0.5) {
      EXPECT_NEAR(sources.removedRadiosity()[e][0], kIndirectAtFloorCentre, 2e-6);
    }
  }

  cube.parameters = test::parameters({{"sources", "10"}});
  Estimate e = estimateRay(*cube.renderer("kok"), kRayToFloorCentre, 100000);
  EXPECT_NEAR(e.mean, (kDirectAtFloorCentre + kIndirectOfTheFloorElement) / kPi, 4 * e.standardError);

  // The fraction rule selects the fewest patches carrying that share of the power.
  selection.fraction = 0.5;
  SecondarySources half(cube.tracer, solution, selection);
  EXPECT_EQ(half.patches().size(), 3u);  // five nearly equal reflectors: three carry over half
}

bool sameSums(const Film &a, const Film &b, size_t p) {
  for (int k = 0; k < kBandCount; ++k)
    if (a.sum[p][k] != b.sum[p][k]) return false;
  return true;
}

/// Whole-image mean with its standard error (pixels are independent).
Estimate imageMean(const Film &film) {
  double sum = 0, variance = 0;
  for (size_t p = 0; p < film.pixelCount(); ++p) {
    sum += film.mean(p).average();
    variance += film.varianceOfMean(p).average();  // bands are correlated: the average's variance is ≤ this
  }
  const double n = double(film.pixelCount());
  return {sum / n, std::sqrt(variance) / n};
}

Film renderFilm(const Scene &scene, const RayTracer &tracer, const std::string &method, const RenderContext &options,
                int size, int spp, int threads = 0, const ParameterValues &parameters = {}) {
  auto renderer = createRenderer(method, tracer, options, parameters);
  PinholeCamera camera(scene.camera, size, size);
  Film film(size, size);
  DriverOptions driver;
  driver.samplesPerPixel = spp;
  driver.threads = threads;
  renderImage(camera, *renderer, driver, film);
  return film;
}

Solution meshAndSolveFor(const Scene &scene, const RayTracer &tracer, const std::string &solver, double meshSize,
                         double tolerance = 1e-4) {
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = meshSize;
  SolverOptions options;
  options.solver = solver;
  options.tolerance = tolerance;
  return meshAndSolve(scene, tracer, meshOptions, options);
}

TEST(TwoPass, NoMethodCountsTheEmittersTwice) {
  // The cube seen from under its light: counting emitters on secondary rays
  // (or reading the solution's direct part on top of the light samples) would
  // add the whole direct image again. Each method's image mean must agree
  // with the path tracer within the noise of both plus the solution's own
  // bias, which `interpolate` shows; the excess is asserted to be far larger.
  Scene scene = test::unitCubeWithCeilingLight();
  RayTracer tracer(scene);
  Solution solution = meshAndSolveFor(scene, tracer, "gauss-seidel", 0.125, 1e-6);
  const int size = 24;
  RenderContext pathOptions;
  Estimate path = imageMean(renderFilm(scene, tracer, "path", pathOptions, size, 1024));
  // max-depth 1: the camera looks down, no emitter in view, so this is the direct image.
  const double excess =
      imageMean(renderFilm(scene, tracer, "path", pathOptions, size, 256, 0, test::parameters({{"max-depth", "1"}})))
          .mean;
  RenderContext options;
  options.solution = &solution;
  Estimate interpolated = imageMean(renderFilm(scene, tracer, "interpolate", options, size, 4));
  const double solutionBias = std::abs(interpolated.mean - path.mean);
  for (const char *method : kTwoPassMethods) {
    Estimate e = imageMean(renderFilm(scene, tracer, method, options, size, 64));
    const double tolerance = 4 * std::hypot(e.standardError, path.standardError) + solutionBias;
    EXPECT_NEAR(e.mean, path.mean, tolerance) << method;
    EXPECT_GT(excess, 5 * tolerance) << method << ": the test could not see a doubled direct term";
    std::cout << method << ": image mean " << e.mean << " vs path " << path.mean << " (tolerance " << tolerance
              << ", doubling would add about " << excess << ")\n";
  }
}

TEST(TwoPass, FurnaceGivesEmissionOverOneMinusReflectanceForEveryMethod) {
  // The furnace's closed form: radiance Le/(1−ρ) everywhere. The hierarchical
  // solution is exact here, so only noise separates the methods from the
  // answer.
  const double rho = 0.5, expected = 1.0 / (1 - rho);
  Scene scene = test::furnace(1.0, rho);
  RayTracer tracer(scene);
  Solution solution = meshAndSolveFor(scene, tracer, "hierarchical", 0.25, 1e-9);
  RenderContext options;
  options.solution = &solution;
  for (const char *method : kTwoPassMethods) {
    Film film = renderFilm(scene, tracer, method, options, 16, 64);
    Estimate e = imageMean(film);
    EXPECT_NEAR(e.mean, expected, 4 * e.standardError + 1e-9) << method;
    for (size_t p = 0; p < film.pixelCount(); ++p) ASSERT_TRUE(film.mean(p).isFinite()) << method;
  }
}

TEST(TwoPass, SameImageWithOneAndTwoThreads) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  Solution solution = meshAndSolveFor(scene, tracer, "progressive", 0.15, 1e-2);
  RenderContext options;
  options.solution = &solution;
  for (const char *method : {"rushmeier", "kok"}) {
    Film one = renderFilm(scene, tracer, method, options, 24, 4, 1);
    Film two = renderFilm(scene, tracer, method, options, 24, 4, 2);
    for (size_t p = 0; p < one.pixelCount(); ++p) ASSERT_TRUE(sameSums(one, two, p)) << method << " pixel " << p;
  }
}

TEST(TwoPass, SelectiveReevaluationSpansInterpolationToTheFullMethod) {
  // Element mode: a threshold no element exceeds gives the interpolated
  // image exactly; one every element exceeds gives the method exactly.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  Solution solution = meshAndSolveFor(scene, tracer, "progressive", 0.15, 1e-2);
  RenderContext options;
  options.solution = &solution;
  Film interpolated = renderFilm(scene, tracer, "interpolate", options, 24, 2);
  Film full = renderFilm(scene, tracer, "shirley", options, 24, 2);
  Film none = renderFilm(scene, tracer, "shirley", options, 24, 2, 0,
                         test::parameters({{"selective", "true"}, {"selective-threshold", "1e300"}}));
  Film all = renderFilm(scene, tracer, "shirley", options, 24, 2, 0,
                        test::parameters({{"selective", "true"}, {"selective-threshold", "0"}}));
  for (size_t p = 0; p < full.pixelCount(); ++p) {
    ASSERT_TRUE(sameSums(none, interpolated, p)) << p;
    ASSERT_TRUE(sameSums(all, full, p)) << p;
  }
  // In between, the flagged pixels are the ones whose element's error is large.
  auto renderer = createRenderer("shirley", tracer, options,
                                 test::parameters({{"selective", "true"}, {"selective-threshold", "0.1"}}));
  const auto &twoPass = dynamic_cast<const TwoPassRenderer &>(*renderer);
  PinholeCamera camera(scene.camera, 24, 24);
  int flagged = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) flagged += twoPass.selectiveWork(camera.generateRay(x + 0.5, y + 0.5)) > 0;
  EXPECT_GT(flagged, 0);
  EXPECT_LT(flagged, 24 * 24);
}

TEST(TwoPass, SelectiveLinksCorrectTheHierarchicalSolutionTowardsThePathTracer) {
  // Link mode: reichert on a hierarchical solution re-evaluates the partially
  // visible links per pixel. With no link selected it is the interpolated
  // image; with the significant ones it moves towards the path tracer in the
  // shadows, where the links' visibility fractions blur the solution.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  Solution solution = meshAndSolveFor(scene, tracer, "hierarchical", 0.15, 1e-3);
  ASSERT_FALSE(solution.links.empty());
  const int size = 32;
  RenderContext options;
  options.solution = &solution;
  Film interpolated = renderFilm(scene, tracer, "interpolate", options, size, 4);
  Film none = renderFilm(scene, tracer, "reichert", options, size, 4, 0,
                         test::parameters({{"selective", "true"}, {"selective-power", "1e300"}}));
  for (size_t p = 0; p < none.pixelCount(); ++p) {
    const Bands a = none.mean(p), b = interpolated.mean(p);
    for (int k = 0; k < kBandCount; ++k) ASSERT_NEAR(a[k], b[k], 1e-12 + 1e-12 * b[k]) << p;
  }
  const ParameterValues links = test::parameters({{"selective", "true"}, {"selective-power", "1e-6"}});
  auto renderer = createRenderer("reichert", tracer, options, links);
  const auto &twoPass = dynamic_cast<const TwoPassRenderer &>(*renderer);
  ASSERT_TRUE(twoPass.selectsByLinks());
  Film corrected = renderFilm(scene, tracer, "reichert", options, size, 16, 0, links);
  RenderContext pathOptions;
  Film path = renderFilm(scene, tracer, "path", pathOptions, size, 512);
  // Compare over the pixels that re-evaluate links: the correction must reduce the error there.
  PinholeCamera camera(scene.camera, size, size);
  double errorBefore = 0, errorAfter = 0;
  int pixels = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (twoPass.selectiveWork(camera.generateRay(x + 0.5, y + 0.5)) <= 0) continue;
      size_t p = size_t(y) * size + x;
      errorBefore += std::abs(interpolated.mean(p).average() - path.mean(p).average());
      errorAfter += std::abs(corrected.mean(p).average() - path.mean(p).average());
      ++pixels;
    }
  ASSERT_GT(pixels, 0);
  EXPECT_LT(errorAfter, errorBefore);
  std::cout << pixels << " pixels re-evaluate links; mean |error| " << errorBefore / pixels << " → "
            << errorAfter / pixels << "\n";
}

TEST(TwoPass, ErrorAgainstThePathTracerFallsAsTheMeshIsRefinedAndSamplesGrow) {
  RADIANT_SKIP_UNDER_SANITIZER();
  // The Cornell box, 8×8-pixel blocks (so the comparison is of light, not of
  // noise): each method's mean relative block error against `path` falls
  // from a coarse solution with few samples to a fine one with more.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  const int size = 48;
  RenderContext pathOptions;
  Film reference = renderFilm(scene, tracer, "path", pathOptions, size, 1024);
  auto blockError = [&](const Film &film) { return test::meanBlockError(film, reference); };
  Solution coarse = meshAndSolveFor(scene, tracer, "progressive", 0.25, 1e-2);
  Solution fine = meshAndSolveFor(scene, tracer, "progressive", 0.06, 1e-3);
  for (const char *method : kTwoPassMethods) {
    RenderContext options;
    options.solution = &coarse;
    double before = blockError(renderFilm(scene, tracer, method, options, size, 4));
    options.solution = &fine;
    double after = blockError(renderFilm(scene, tracer, method, options, size, 64));
    EXPECT_LT(after, before) << method;
    EXPECT_LT(after, 0.05) << method;
    std::cout << method << ": block error " << before << " (0.25 m, few samples) → " << after
              << " (0.06 m, more samples)\n";
  }
}

// kok moves the selected sources' light from the solution to per-pixel
// samples, so in expectation it is shirley. Its cosine-sampled ray weighs
// itself against the source samples by the density of the patch it lands
// on; in scenes/two-rooms the walls are cut where the divider pierces them,
// so a selected source is often not its face's first patch, and taking that
// patch's density (0 when it was not selected) lost the light those rays
// found: kok was 15–25 % darker than shirley there.
TEST(TwoPass, KokAgreesWithShirleyWhereASourceIsOneOfSeveralPatchesOfAFace) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/two-rooms/scene.json");
  RayTracer tracer(scene);
  // Faces cut where the divider meets them, as the default solver meshes them.
  const std::vector<FaceSplit> splits = splitFaces(scene, tracer);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.3;
  mesh.faceSplits = &splits;
  Solution solution = initialSolution(scene, buildMesh(scene, mesh));
  SolverOptions solver;
  solver.solver = "gauss-seidel";
  solver.tolerance = 1e-3;
  solveRadiosity(tracer, solution, solver);
  size_t cutFaces = 0;
  for (uint32_t count : solution.mesh.facePatchCount) cutFaces += count > 1;
  ASSERT_GT(cutFaces, 0u);
  RenderContext options;
  options.solution = &solution;
  const Estimate shirley = imageMean(renderFilm(scene, tracer, "shirley", options, 24, 16));
  const Estimate kok =
      imageMean(renderFilm(scene, tracer, "kok", options, 24, 16, 0, test::parameters({{"sources", "8"}})));
  EXPECT_NEAR(kok.mean, shirley.mean, 4 * std::hypot(kok.standardError, shirley.standardError) + 0.01 * shirley.mean);
}

TEST(TwoPass, ShirleyAndKokDoNotCountUnshotEmissionTwice) {
  // Progressive refinement stopped after one shot: most emission is still
  // unshot and lives in the ambient term. The emitter samples count its first
  // arrival, so only the rest of the ambient may be added (in the furnace the
  // ambient term of Cohen, Chen, Wallace & Greenberg 1988 makes every
  // iteration exact, so the image must still be Le/(1−ρ)).
  const double rho = 0.5, expected = 1.0 / (1 - rho);
  Scene scene = test::furnace(1.0, rho);
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.25;
  SolverOptions solverOptions;
  solverOptions.solver = "progressive";
  solverOptions.maxIterations = 1;
  Solution solution = meshAndSolve(scene, tracer, meshOptions, solverOptions);
  ASSERT_EQ(solution.stats.iterations, 1);
  RenderContext options;
  options.solution = &solution;
  for (const char *method : {"shirley", "kok"}) {
    Estimate e = imageMean(renderFilm(scene, tracer, method, options, 16, 64));
    // The ambient term is exact for the mean, not point by point: after one
    // shot the interpolated indirect strays ~10⁻⁴ from uniform, which the
    // sampled direct light's noise used to hide and the exact one does not.
    EXPECT_NEAR(e.mean, expected, 4 * e.standardError + 1e-3 * expected) << method;
    // Adding the whole ambient would show ρ·Le·(1 − share already shot) too much: far outside.
    EXPECT_GT(rho * 0.9, 10 * (4 * e.standardError)) << method;
  }
}

}  // namespace
// A hierarchical solution refines the walls behind a shadow to thousands of
// leaves; kok then removes the selected patches' light, at each receiver,
// from the leaves near it and from inner tree nodes (their leaves' mean) it
// sees under a small angle, or pairing every leaf with every receiver would
// take minutes. The removal must still be the same light: its total within
// 0.5 %, and element by element within 2 % of the largest removal (what a
// node's piecewise-constant mean misses where its form factor varies).
TEST(TwoPass, KokRemovesTheSameLightFromCoarserSourcePieces) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  SolverOptions solver;
  solver.solver = "hierarchical-exact";
  // Coarser than draft: the leaf-by-leaf removal below is 10⁷ form factors at draft.
  solver.linkError = 0.03, solver.directTolerance = 0.05;
  const Solution solution = meshAndSolve(scene, tracer, MeshOptions{}, solver);
  SecondarySourceOptions options;
  options.count = 2;  // the two brightest reflectors: the leaf-by-leaf sum stays a few seconds
  options.visibilityGrid = 2;
  // The reference goes the way of a uniform mesh, element by element, not
  // through the trees at all: a tree piece built wrong cannot hide in both.
  Solution flat = solution;
  for (Patch &patch : flat.mesh.patches) patch.treeRoot = -1;
  const SecondarySources every(tracer, flat, options);
  const SecondarySources trees(tracer, solution, options);
  ASSERT_EQ(every.patches(), trees.patches());
  size_t leaves = 0;
  for (uint32_t p : trees.patches()) leaves += solution.mesh.patches[p].elementCount;
  EXPECT_EQ(trees.sourceElementCount(), leaves);
  EXPECT_LE(every.piecesPerReceiver(), double(leaves));
  std::cout << every.sourceElementCount() << " source elements; per receiver: " << every.piecesPerReceiver()
            << " leaves, " << trees.piecesPerReceiver() << " pieces\n";
  EXPECT_LT(trees.piecesPerReceiver(), 0.1 * every.piecesPerReceiver());
  double everyTotal = 0, treesTotal = 0, worst = 0, largest = 0;
  for (uint32_t e = 0; e < solution.elementCount(); ++e)
    largest = std::max(largest, every.removedRadiosity()[e].average());
  for (uint32_t e = 0; e < solution.elementCount(); ++e) {
    const double a = solution.mesh.elements[e].area, f = every.removedRadiosity()[e].average(),
                 c = trees.removedRadiosity()[e].average();
    everyTotal += a * f, treesTotal += a * c;
    worst = std::max(worst, std::abs(c - f) / largest);
  }
  std::cout << "removed power: every leaf " << everyTotal << ", trees " << treesTotal << "; worst element " << worst
            << " of the largest removal\n";
  EXPECT_NEAR(treesTotal / everyTotal, 1.0, 0.005);
  EXPECT_LT(worst, 0.02);
}

}  // namespace radiant
