// The radiosity stage: mesh, solvers, solution file, against closed forms.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

#include "film_metrics.h"
#include "io/solution_file.h"
#include "mesh/mesh.h"
#include "radiosity/report.h"
#include "radiosity/solver.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render/renderer.h"
#include "sanitizer.h"
#include "scene/load_scene.h"
#include "solution_file_checks.h"
#include "test_scenes.h"
#include "util/error.h"

namespace radiant {
namespace {

Solution solve(const Scene &scene, const std::string &solver, double meshSize, double tolerance = 1e-6,
               int maxIterations = 0, int visibilitySamples = 4) {
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = meshSize;
  Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
  SolverOptions options;
  options.solver = solver;
  options.tolerance = tolerance;
  options.maxIterations = maxIterations;
  options.visibilitySamples = visibilitySamples;
  solveRadiosity(tracer, s, options);
  return s;
}

TEST(Mesh, SubdivisionCoversEachFaceWithSharedNodes) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  MeshOptions options;
  options.maxEdgeLength = 0.05;
  RadiosityMesh mesh = buildMesh(scene, options);
  ASSERT_EQ(mesh.patches.size(), scene.faces.size());
  for (const Patch &p : mesh.patches) {
    double area = 0;
    for (uint32_t e = p.firstElement; e < p.firstElement + p.elementCount; ++e) {
      area += mesh.elements[e].area;
      // Elements are no larger than asked (their diagonal bounds the edge).
      for (const Vec3 &v : mesh.polygon(e)) EXPECT_LT(length(v - mesh.elements[e].centre), 0.05 * 1.5);
    }
    EXPECT_NEAR(area, p.area, 1e-9 * p.area) << "patch of face " << p.face;
    // A grid shares its nodes: (nU+1)(nV+1) for quads, (n+1)(n+2)/2 for triangles.
    uint32_t expected = p.vertexCount == 4 ? uint32_t((p.divisionsU + 1) * (p.divisionsV + 1))
                                           : uint32_t((p.divisionsU + 1) * (p.divisionsU + 2) / 2);
    EXPECT_EQ(p.nodeCount, expected);
  }
}

TEST(Mesh, LocateFindsTheElementContainingAPoint) {
  // Random points inside each element must be located in that element, and the
  // interpolation weights must reproduce the point from the element's nodes.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  MeshOptions options;
  options.maxEdgeLength = 0.07;
  RadiosityMesh mesh = buildMesh(scene, options);
  Pcg32 rng(4, 4);
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    std::vector<Vec3> poly = mesh.polygon(e);
    double a = 0.05 + 0.9 * rng.next(), b = 0.05 + 0.9 * rng.next();
    Vec3 p = element.vertexCount == 4
                 ? poly[0] * ((1 - a) * (1 - b)) + poly[1] * (a * (1 - b)) + poly[2] * (a * b) + poly[3] * ((1 - a) * b)
                 : poly[0] * (1 - a * (1 - b * 0.5) - b * (1 - a) * 0.5) + poly[1] * (a * (1 - b * 0.5)) +
                       poly[2] * (b * (1 - a) * 0.5);
    MeshLocation l = mesh.locate(mesh.patches[element.patch].face, p);
    ASSERT_EQ(l.element, e);
    std::array<double, 4> w = mesh.nodeWeights(l);
    Vec3 back;
    for (int k = 0; k < element.vertexCount; ++k) back += poly[k] * w[k];
    EXPECT_LT(length(back - p), 1e-9);
  }
}

class FurnaceSolution : public ::testing::TestWithParam<double> {};

TEST_P(FurnaceSolution, GaussSeidelGivesEmissionOverOneMinusReflectanceEverywhere) {
  // Closed convex box: the contour-integral form factors of a row sum to 1
  // exactly, so B = E/(1−ρ) on every element up to the sweep tolerance.
  const double rho = GetParam(), E = 1.0 * kPi;  // emitted radiance 1 → exitance π
  Solution s = solve(test::furnace(1.0, rho), "gauss-seidel", 0.25, 1e-9);
  for (size_t e = 0; e < s.elementCount(); ++e)
    for (int b = 0; b < kBandCount; ++b) ASSERT_NEAR(s.radiosity[e][b], E / (1 - rho), 1e-6 * E / (1 - rho));
  // Energy balance of a closed scene: all that is emitted is absorbed.
  EXPECT_NEAR(s.stats.absorbedPower.average(), s.stats.emittedPower.average(), 1e-6 * s.stats.emittedPower.average());
}

TEST_P(FurnaceSolution, ProgressiveAmbientIsExactBeforeTheFirstShot) {
  // With uniform E and ρ the display corrected by the ambient term (Cohen,
  // Chen, Wallace & Greenberg 1988) is the furnace's E/(1−ρ) at iteration 0.
  const double rho = GetParam(), E = kPi;
  Solution s = solve(test::furnace(1.0, rho), "progressive", 0.25, /*tolerance above any residual*/ 2.0);
  EXPECT_EQ(s.stats.iterations, 0);
  for (size_t e = 0; e < s.elementCount(); ++e)
    for (int b = 0; b < kBandCount; ++b)
      ASSERT_NEAR(s.displayRadiosity(static_cast<uint32_t>(e))[b], E / (1 - rho), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Radiosity, FurnaceSolution, ::testing::Values(0.0, 0.5, 0.9));

TEST(Radiosity, ProgressiveConvergesInTheFurnace) {
  // Shooting with ray-cast form factors: each F(dA_j → A_i) is Wallace's disc
  // estimate, so rows do not sum to exactly 1; the furnace value is then
  // E/(1−ρ·s) with s the row sum. For 0.25 m elements in a 1 m box the disc
  // approximation's defect is within a few percent, which bounds the tolerance.
  const double rho = 0.5, E = kPi;
  Solution s = solve(test::furnace(1.0, rho), "progressive", 0.25, 1e-4);
  EXPECT_LT(s.stats.residual, 1e-4);
  for (size_t e = 0; e < s.elementCount(); ++e)
    EXPECT_NEAR(s.displayRadiosity(static_cast<uint32_t>(e)).average(), E / (1 - rho), 0.03 * E / (1 - rho));
}

TEST(Radiosity, DirectPlusIndirectPlusEmissionIsTheRadiosity) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  std::vector<double> directPower;
  for (const char *solver : {"gauss-seidel", "progressive"}) {
    Solution s = solve(scene, solver, 0.1, 1e-4);
    double directSum = 0, indirectSum = 0;
    for (size_t e = 0; e < s.elementCount(); ++e) {
      Bands sum = s.emission[e] + s.direct[e] + s.indirect[e];
      for (int b = 0; b < kBandCount; ++b) ASSERT_NEAR(sum[b], s.radiosity[e][b], 1e-9 * (1 + s.radiosity[e][b]));
      directSum += s.direct[e].average() * s.mesh.elements[e].area;
      indirectSum += s.indirect[e].average() * s.mesh.elements[e].area;
    }
    EXPECT_GT(directSum, 0) << solver;
    EXPECT_GT(indirectSum, 0) << solver;
    directPower.push_back(directSum);
  }
  // The direct part is one bounce from the light: both solvers must find the same.
  EXPECT_NEAR(directPower[1] / directPower[0], 1.0, 0.01);
}

TEST(Radiosity, GaussSeidelAndProgressiveAgreeOnTheCornellBox) {
  RADIANT_SKIP_UNDER_SANITIZER();
  // Gathering and shooting on the same mesh solve the same equations: the
  // power escaping through the open front, and each surface's mean
  // radiosity, agree up to the noise of the visibility estimates. With 4
  // shadow rays per form factor a small face in partial shadow (the short
  // block's front, 9 elements) differs by 10%; with 36 the noise is below 2%.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution gs = solve(scene, "gauss-seidel", 0.08, 1e-5, 0, 36);
  Solution pr = solve(scene, "progressive", 0.08, 1e-5, 0, 36);
  ASSERT_EQ(gs.elementCount(), pr.elementCount());
  EXPECT_NEAR(pr.stats.escapedPower.average() / gs.stats.escapedPower.average(), 1.0, 0.05);
  for (const Patch &p : gs.mesh.patches) {
    double a = 0, b = 0;
    for (uint32_t e = p.firstElement; e < p.firstElement + p.elementCount; ++e) {
      a += gs.radiosity[e].average() * gs.mesh.elements[e].area;
      b += pr.displayRadiosity(e).average() * pr.mesh.elements[e].area;
    }
    EXPECT_NEAR(b / a, 1.0, 0.05) << scene.objects[p.object].name;
  }
}

TEST(SolutionFile, RoundTripsAndRefusesAnotherScene) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution s = solve(scene, "progressive", 0.15, 1e-2);
  auto dir = std::filesystem::temp_directory_path() / "radiant-solution-test";
  std::filesystem::create_directories(dir);
  std::string path = (dir / "box.rad").string();
  writeSolution(s, scene, path);
  Solution back = readSolution(path, scene);
  ASSERT_EQ(back.elementCount(), s.elementCount());
  // Format 7 stores the values as f32 and derives B and the node values from
  // them (solution_file_checks.h says what holds); the mesh comes back exactly.
  test::expectSolutionReadBack(s, back);
  // Written again, it reads back bit for bit: a second round trip changes nothing.
  writeSolution(back, scene, path);
  test::expectBitIdentical(back, readSolution(path, scene));
  EXPECT_EQ(back.stats.solver, "progressive");

  Scene other = scene;
  other.materials[0].diffuse[0] *= 0.5;
  try {
    readSolution(path, other);
    FAIL() << "a solution for another scene was accepted";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("another scene"), std::string::npos) << e.what();
  }
  // Truncated and foreign files are clear errors, not crashes.
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  EXPECT_THROW(readSolution(path, scene), InputError);
  std::ofstream(path) << "not a solution";
  EXPECT_THROW(readSolution(path, scene), InputError);
  std::filesystem::remove_all(dir);
}

TEST(SolutionFile, RefusesVersion6) {
  // A file of the previous format (its version field at byte 16) is refused
  // with the message that says to solve again, before anything else is read.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution s = solve(scene, "progressive", 0.3, 1e-2);
  const std::string path = (std::filesystem::temp_directory_path() / "radiant-solution-v6.rad").string();
  writeSolution(s, scene, path);
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    const uint32_t six = 6;
    file.seekp(16);
    file.write(reinterpret_cast<const char *>(&six), sizeof six);
  }
  try {
    readSolution(path, scene);
    ADD_FAILURE() << "a version-6 file was accepted";
  } catch (const InputError &e) {
    EXPECT_NE(
        std::string(e.what()).find("solution format version 6; this radiant reads version 7 (solve the scene again)"),
        std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

/// scenes/cornell-sphere-1m with a coarser sphere: the same kind of mesh (most
/// elements are triangles of the sphere, one element per patch, the floor cut
/// under the sphere), a few thousand elements instead of half a million.
Scene tessellatedSphereScene(int segments) {
  std::ifstream in(RADIANT_SOURCE_DIR "/scenes/cornell-sphere-1m/scene.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  const std::string key = "\"segments\": 1000";
  const size_t at = json.find(key);
  EXPECT_NE(at, std::string::npos);
  json.replace(at, key.size(), "\"segments\": " + std::to_string(segments));
  return parseSceneJson(json, RADIANT_SOURCE_DIR "/scenes/cornell-sphere-1m/scene.json");
}

TEST(SolutionFile, AtMost100BytesPerElementOfALargeMesh) {
  // Issue 20: the file of a large scene at most 100 bytes per element. The
  // large scene's elements are mostly one-element patches (the sphere's
  // triangles), the costliest case per element: a patch record (17 bytes)
  // beside the element's direct, indirect, irradiance and unshot values (48).
  // Its 510 110 elements measured 65.5 bytes each (docs/solution-format.md);
  // this is the same scene with 3 160 sphere triangles instead of a million
  // (3 772 elements; 62.7 bytes each when measured).
  Scene scene = tessellatedSphereScene(80);
  RayTracer tracer(scene);
  MeshOptions mesh;
  SolverOptions solver;
  solver.solver = "stochastic";
  solver.tolerance = 1e-2;
  Solution s = meshAndSolve(scene, tracer, mesh, solver);
  ASSERT_GT(s.elementCount(), 3000u);
  ASSERT_FALSE(s.mesh.nodeOnCut.empty());  // the floor is cut under the sphere: that is kept too
  const std::string path = (std::filesystem::temp_directory_path() / "radiant-solution-size.rad").string();
  writeSolution(s, scene, path);
  const double bytesPerElement = double(std::filesystem::file_size(path)) / double(s.elementCount());
  EXPECT_LE(bytesPerElement, 100.0);
  EXPECT_GE(bytesPerElement, 48.0);  // the values themselves: nothing was left out
  test::expectSolutionReadBack(s, readSolution(path, scene));
  std::filesystem::remove(path);
}

TEST(Radiosity, SolutionDoesNotDependOnThreadCount) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.15;
  for (const char *solver : {"gauss-seidel", "progressive", "hierarchical", "stochastic"}) {
    Solution a = initialSolution(scene, buildMesh(scene, meshOptions)), b = a;
    SolverOptions options;
    options.solver = solver;
    options.threads = 1;
    solveRadiosity(tracer, a, options);
    options.threads = 2;
    solveRadiosity(tracer, b, options);
    for (size_t e = 0; e < a.elementCount(); ++e) ASSERT_EQ(a.radiosity[e][0], b.radiosity[e][0]) << solver;
  }
}

TEST(Radiosity, UnknownSolverAndHugeMeshAreClearErrors) {
  Scene scene = test::furnace(1.0, 0.5);
  EXPECT_THROW(solve(scene, "jacobi-typo", 0.5), InputError);
  MeshOptions tiny;
  tiny.maxEdgeLength = 1e-6;
  tiny.maxElements = 1000;
  EXPECT_THROW(buildMesh(scene, tiny), InputError);
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

TEST(SurfaceReport, FurnaceRowsHaveTheClosedFormPhotometry) {
  // Furnace with L_e = 1 W/(sr·m²), ρ = 0.5: B = H = 2π W/m² everywhere, so the
  // luminance is 683·B/π = 1366 cd/m² and the illuminance 683·2π = 4291.5 lux.
  Scene scene = test::furnace(1.0, 0.5);
  scene.objects[0].name = "box, \"inside\"";  // exercises CSV quoting
  Solution s = solve(scene, "gauss-seidel", 0.5, 1e-12);
  auto path = std::filesystem::temp_directory_path() / "radiant-report-test.csv";
  writeSurfaceReport(s, scene, path.string());
  std::ifstream in(path);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header.substr(0, 15), "object,area_m2,");
  ASSERT_EQ(row.substr(0, 20), "\"box, \"\"inside\"\"\",6,");
  std::vector<double> values;
  std::stringstream fields(row.substr(20));
  for (std::string field; std::getline(fields, field, ',');) values.push_back(std::stod(field));
  ASSERT_EQ(values.size(), 8u);
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(values[b], 2 * kPi, 1e-6);  // radiosity
  for (int b = 3; b < 6; ++b) EXPECT_NEAR(values[b], 2 * kPi, 1e-6);  // irradiance
  EXPECT_NEAR(values[6], 683.0 * 2, 1e-3);                            // cd/m²
  EXPECT_NEAR(values[7], 683.0 * 2 * kPi, 1e-3);                      // lux
  std::filesystem::remove(path);
}

/// Renders the Cornell box's view small, for comparing a radiosity display
/// with the path tracer. Error: the mean over 8×8-pixel blocks of
/// |block mean − reference block mean| / reference, which averages the path
/// tracer's noise down (at 512 spp its block means are within ~0.3%).
struct ImageAgainstPath {
  const Scene &scene;
  const RayTracer &tracer;
  int size;
  PinholeCamera camera{scene.camera, size, size};
  Film reference = render("path", nullptr, 512);

  Film render(const std::string &method, const Solution *solution, int spp) const {
    RenderContext options;
    options.solution = solution;
    auto renderer = createRenderer(method, tracer, options);
    Film film(size, size);
    DriverOptions driver;
    driver.samplesPerPixel = spp;
    renderImage(camera, *renderer, driver, film);
    return film;
  }
  double blockError(const Solution &solution) const {
    return test::meanBlockError(render("interpolate", &solution, 4), reference);
  }
};

TEST(Radiosity, InterpolatedImageApproachesThePathTracerAsTheMeshIsRefined) {
  RADIANT_SKIP_UNDER_SANITIZER();
  // The classic radiosity image converges to the reference as elements shrink.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  ImageAgainstPath image{scene, tracer, 64};
  std::vector<double> errors;
  for (double meshSize : {0.2, 0.1, 0.05}) {
    Solution s = solve(scene, "progressive", meshSize, 1e-3);
    errors.push_back(image.blockError(s));
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(errors[2], 0.1);
  std::cout << "block errors at 0.2, 0.1, 0.05 m: " << errors[0] << " " << errors[1] << " " << errors[2] << "\n";
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

TEST(Hierarchical, FurnaceGivesEmissionOverOneMinusReflectanceOnEveryLeaf) {
  // In a closed convex box every receiver's links, at whatever level, must
  // cover the whole environment exactly once: then B = E/(1−ρ) everywhere.
  for (double rho : {0.5, 0.9}) {
    Scene scene = test::furnace(1.0, rho);
    Solution s = solve(scene, "hierarchical", 0.125, 1e-9);
    ASSERT_GT(s.links.size(), 0u);
    for (size_t e = 0; e < s.elementCount(); ++e)
      ASSERT_NEAR(s.radiosity[e][0], kPi / (1 - rho), 1e-6 * kPi / (1 - rho)) << "ρ " << rho << ", leaf " << e;
  }
}

TEST(Hierarchical, MaxElementsBoundsTheRefinement) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.01;
  Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
  SolverOptions options;
  options.solver = "hierarchical";
  options.maxElements = 500;
  solveRadiosity(tracer, s, options);
  EXPECT_LE(s.elementCount(), 500u);
  EXPECT_GT(s.elementCount(), 400u);  // it refines up to the bound
}

TEST(Hierarchical, PushPullConservesPower) {
  // A node's radiosity is the area-weighted mean of its children's, so each
  // root carries exactly the power of its leaves.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution s = solve(scene, "hierarchical", 0.05, 1e-6);
  ASSERT_EQ(s.treeRadiosity.size(), s.mesh.tree.size());
  for (const Patch &p : s.mesh.patches) {
    ASSERT_GE(p.treeRoot, 0);
    double leaves = 0;
    for (uint32_t e = p.firstElement; e < p.firstElement + p.elementCount; ++e)
      leaves += s.radiosity[e].average() * s.mesh.elements[e].area;
    double root = s.treeRadiosity[p.treeRoot].average() * s.mesh.tree[p.treeRoot].area;
    EXPECT_NEAR(root, leaves, 1e-9 * (1 + leaves));
  }
}

TEST(Hierarchical, TinyThresholdReproducesGaussSeidelOnTheSameLeaves) {
  // Unit box, ceiling emitter, mesh 0.25 m: with a threshold of 0 every pair is
  // refined to the minimum area, so the leaves are GS's 4×4 elements per face.
  // The two differ only in how a form factor is integrated over the receiver
  // (GS: its centre; HR: a 4×4 grid), which moves element values next to the
  // box's edges (measured: 0.8% at worst, 0.08% in the area-weighted mean).
  const int walls[6] = {0, 0, 0, 1, 0, 0};
  Scene scene = test::closedBox(1.0, walls);
  Material wall, light;
  wall.diffuse = Bands(0.5);
  light.diffuse = Bands(0.0);
  light.emission = Bands(1.0 / kPi);
  scene.materials = {wall, light};
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.25;
  Solution gs = initialSolution(scene, buildMesh(scene, meshOptions)), hr = gs;
  SolverOptions options;
  options.tolerance = 1e-9;
  options.solver = "gauss-seidel";
  solveRadiosity(tracer, gs, options);
  options.solver = "hierarchical";
  options.linkThreshold = 0;
  solveRadiosity(tracer, hr, options);
  ASSERT_EQ(hr.elementCount(), gs.elementCount());
  double gsMean = 0, hrMean = 0, worst = 0;
  for (uint32_t e = 0; e < hr.elementCount(); ++e) {
    const Element &leaf = hr.mesh.elements[e];
    MeshLocation l = gs.mesh.locate(hr.mesh.patches[leaf.patch].face, leaf.centre);
    double a = gs.radiosity[l.element].average(), b = hr.radiosity[e].average();
    EXPECT_NEAR(b, a, 0.02 * a + 1e-12) << "leaf " << e;
    worst = std::max(worst, std::abs(b - a) / a);
    gsMean += a * leaf.area;
    hrMean += b * leaf.area;
  }
  EXPECT_NEAR(hrMean / gsMean, 1.0, 0.003);
  std::cout << "hierarchical / gauss-seidel: worst element " << worst << ", mean " << hrMean / gsMean << "\n";
}

TEST(Hierarchical, LinksRecordVisibilityAndTheSolutionFileKeepsThem) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution s = solve(scene, "hierarchical", 0.05, 1e-4);
  size_t counts[3] = {0, 0, 0};
  for (const Link &l : s.links) {
    ++counts[int(l.visibility)];
    EXPECT_GE(l.formFactor, 0);
    EXPECT_LE(l.formFactor, 1);
    if (l.visibility == LinkVisibility::Full) {
      EXPECT_EQ(l.visibleFraction, 1.0f);
    }
    if (l.visibility == LinkVisibility::None) {
      EXPECT_EQ(l.formFactor, 0.0f);
    }
  }
  EXPECT_GT(counts[int(LinkVisibility::Partial)], 0u);  // the blocks cast shadows
  EXPECT_GT(counts[int(LinkVisibility::Full)], counts[int(LinkVisibility::Partial)]);

  auto path = (std::filesystem::temp_directory_path() / "radiant-hierarchical.rad").string();
  writeSolution(s, scene, path);
  Solution back = readSolution(path, scene);
  std::filesystem::remove(path);
  ASSERT_EQ(back.links.size(), s.links.size());
  ASSERT_EQ(back.mesh.tree.size(), s.mesh.tree.size());
  EXPECT_EQ(back.links[7].source, s.links[7].source);
  EXPECT_EQ(back.mesh.tVertices.size(), s.mesh.tVertices.size());
  test::expectSolutionReadBack(s, back);  // trees, T-vertices and links exactly, values within f32
  // Point location goes through the saved trees.
  for (uint32_t e = 0; e < s.elementCount(); e += 37) {
    const Element &leaf = s.mesh.elements[e];
    EXPECT_EQ(back.mesh.locate(s.mesh.patches[leaf.patch].face, leaf.centre).element, e);
  }
}

TEST(Hierarchical, InterpolationHasNoCracksAtTVertices) {
  // Along every coarse leaf's edge, the nodes of finer neighbours carry the
  // value the coarse leaf interpolates there, so the shading is continuous.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution s = solve(scene, "hierarchical", 0.025, 1e-4);
  ASSERT_GT(s.mesh.tVertices.size(), 0u);
  for (const RadiosityMesh::TVertex &t : s.mesh.tVertices) {
    Bands expected = (s.nodeRadiosity[t.edgeStart] + s.nodeRadiosity[t.edgeEnd]) * 0.5;
    EXPECT_NEAR(s.nodeRadiosity[t.node][1], expected[1], 1e-12);
    Vec3 mid = (s.mesh.nodes[t.edgeStart] + s.mesh.nodes[t.edgeEnd]) * 0.5;
    EXPECT_LT(length(mid - s.mesh.nodes[t.node]), 1e-12);
  }
}

TEST(Mesh, ALongDiagonalEdgeAmongTinyFacetsIsJoinedInItsLengthsTime) {
  // The T-vertices across patches bin each element edge on a grid of the
  // mean edge length. 10⁴ facets of 1 mm make that grid about 5 mm fine; the
  // 4–5 m lattice edges of two large triangles, diagonal in all three axes,
  // then span ~900 cells along each: binned by their boxes, 10⁹ cells each
  // (an allocation that fails, or hours); walked along their length, 10³
  // steps. The triangles meet along the diagonal with different lattices,
  // and the walk must still find every T-vertex there.
  Scene scene;
  scene.objects.push_back({"test", "test"});
  Material grey;
  grey.diffuse = Bands(0.5);
  scene.materials = {grey};
  for (int i = 0; i < 10000; ++i) {
    const double x = 40 + 0.002 * (i % 100), z = 0.002 * (i / 100);
    test::addQuad(scene, {{x, 0, z}, {x, 0, z + 0.001}, {x + 0.001, 0, z + 0.001}, {x + 0.001, 0, z}}, 0);
  }
  auto addTriangle = [&](const Vec3 &a, const Vec3 &b, const Vec3 &c) {
    Face f;
    f.vertexCount = 3;
    f.material = 0;
    for (int k = 0; k < 3; ++k) f.vertices[k] = uint32_t(scene.positions.size() + k);
    scene.positions.insert(scene.positions.end(), {a, b, c});
    scene.addFace(f);
  };
  // One plane (y = x), facing one way, the shared edge from (0, 0, 0) to
  // (10, 10, 10) (17.3 m). With 5 m elements the first triangle's lattice
  // has ⌈17.3 / 5⌉ = 4 divisions (its longest edge is the diagonal), the
  // second's ⌈36.7 / 5⌉ = 8 (its longest runs to (25, 25, −10)): along the
  // diagonal the second's nodes at odd eighths lie inside the first's
  // edges, 4 T-vertices, and the first's nodes are all the second's.
  addTriangle({0, 0, 0}, {10, 10, 10}, {0, 0, 10});
  addTriangle({0, 0, 0}, {25, 25, -10}, {10, 10, 10});
  MeshOptions options;
  options.maxEdgeLength = 5.0;          // each large triangle a lattice; the facets whole
  options.crossPatchTVertices = false;  // added below, timed
  RadiosityMesh mesh = buildMesh(scene, options);
  ASSERT_TRUE(mesh.tVertices.empty());
  ASSERT_EQ(mesh.patches[10000].divisionsU, 4);
  ASSERT_EQ(mesh.patches[10001].divisionsU, 8);
  const auto start = std::chrono::steady_clock::now();
  mesh.addCrossPatchTVertices();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  for (const RadiosityMesh::TVertex &t : mesh.tVertices) {
    const Vec3 &p = mesh.nodes[t.node];
    EXPECT_NEAR(p.x, p.z, 1e-9);  // on the diagonal x = y = z; none among the facets
    EXPECT_NEAR(t.t, 0.5, 1e-6);  // an odd eighth: the middle of a quarter
  }
  EXPECT_EQ(mesh.tVertices.size(), 4u);
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

TEST(Stochastic, FurnaceMeanIsExactAndElementsWithinNoise) {
  // In a closed box no ray escapes, so the power is exact up to what is left
  // unshot; each element's value is a Monte Carlo estimate whose relative
  // noise is about 1/√(rays that hit it). First iteration: N = 64·n rays,
  // spread over the elements roughly by area.
  const double rho = 0.5, expected = kPi / (1 - rho);
  Scene scene = test::furnace(1.0, rho);
  Solution s = solve(scene, "stochastic", 0.1, 1e-6);
  double area = 0, power = 0;
  for (size_t e = 0; e < s.elementCount(); ++e) {
    area += s.mesh.elements[e].area;
    power += s.radiosity[e].average() * s.mesh.elements[e].area;
  }
  EXPECT_NEAR(power / area, expected, 1e-5 * expected);
  const double raysPerElement = 64;
  for (size_t e = 0; e < s.elementCount(); ++e) {
    double sigma = expected * rho / std::sqrt(raysPerElement);  // the reflected part carries the noise
    EXPECT_NEAR(s.radiosity[e][0], expected, 5 * sigma) << "element " << e;
  }
}

TEST(Stochastic, AgreesWithHierarchicalOnTheCornellBox) {
  // Both estimate element-averaged (Galerkin) transport: the stochastic solver
  // by rays from anywhere on an element, the hierarchical one by a 4×4
  // receiver grid. (Gauss–Seidel and progressive collocate at element
  // centres and let ~3% less power escape on this mesh.)
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution gs = solve(scene, "hierarchical", 0.08, 1e-5);
  Solution mc = solve(scene, "stochastic", 0.08, 1e-4);
  std::cout << "escaped: hierarchical " << gs.stats.escapedPower.average() << ", stochastic "
            << mc.stats.escapedPower.average() << "\n";
  EXPECT_NEAR(mc.stats.escapedPower.average() / gs.stats.escapedPower.average(), 1.0, 0.02);
  // Direct and indirect are kept apart: the first iteration is all emission.
  double directGs = 0, directMc = 0;
  for (size_t e = 0; e < gs.elementCount(); ++e) directGs += gs.direct[e].average() * gs.mesh.elements[e].area;
  for (size_t e = 0; e < mc.elementCount(); ++e) directMc += mc.direct[e].average() * mc.mesh.elements[e].area;
  EXPECT_NEAR(directMc / directGs, 1.0, 0.02);
}

namespace {

/// A scene of `faces` front faces, `emitters` of them emitting: all chooseSolver counts.
Scene sceneOfFaces(size_t faces, size_t emitters) {
  Scene scene;
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  scene.materials.resize(2);
  scene.materials[1].emission = Bands(1.0);
  scene.faces.resize(faces);
  for (size_t f = 0; f < faces; ++f) scene.faces[f] = Face{3, {0, 1, 2}}, scene.faces[f].material = f < emitters;
  return scene;
}

SolverChoice chooseFor(const Scene &scene, const std::string &solver, bool importance = false) {
  SolverOptions options;
  options.solver = solver;
  options.importance = importance;
  return chooseSolver(scene, options);
}

}  // namespace

TEST(Radiosity, ASceneWithoutFacesIsRefusedNotSolved) {
  Scene empty;
  empty.sourceFile = "empty.obj";
  const RayTracer tracer(empty);
  for (const char *solver : {"auto", "stochastic", "hierarchical-exact"}) {
    SolverOptions options;
    options.solver = solver;
    try {
      meshAndSolve(empty, tracer, MeshOptions{}, options);
      ADD_FAILURE() << solver << ": no error";
    } catch (const InputError &e) {
      EXPECT_EQ(e.location().file, "empty.obj");
      EXPECT_NE(std::string(e.what()).find("no faces"), std::string::npos) << e.what();
    }
  }
}

TEST(Radiosity, AutoPicksHierarchicalExactUpTo2000PatchesAndStochasticBeyond) {
  EXPECT_EQ(chooseFor(sceneOfFaces(2000, 1), "auto").solver, "hierarchical-exact");
  EXPECT_EQ(chooseFor(sceneOfFaces(2001, 1), "auto").solver, "stochastic");
  EXPECT_EQ(chooseFor(sceneOfFaces(2000, 1), "auto", true).solver, "hierarchical");
  EXPECT_EQ(chooseFor(sceneOfFaces(2001, 1), "auto", true).solver, "stochastic");
  EXPECT_EQ(chooseFor(sceneOfFaces(1000, 256), "auto").solver, "hierarchical-exact");
  EXPECT_EQ(chooseFor(sceneOfFaces(1000, 257), "auto").solver, "stochastic");
  EXPECT_EQ(chooseFor(sceneOfFaces(10, 1), "gauss-seidel").solver, "gauss-seidel");
  Scene room = test::furnace(1.0, 0.5);
  EXPECT_EQ(solve(room, "auto", 0.5, 1e-3).stats.solver, "hierarchical-exact");
}

TEST(Radiosity, AutoPicksStochasticForAFurnaceOfThousandsOfPatches) {
  // A box whose walls are each cut into 25 × 25 quads, all emitting: 3750
  // patches, and as many emitters.
  // The furnace: B = E/(1 − ρ) = 2 everywhere.
  Scene many;
  many.objects.push_back({"cut box", "test"});
  Material wall;
  wall.diffuse = Bands(0.5);
  wall.emission = Bands(1.0);
  many.materials.push_back(wall);
  const int cuts = 25;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < cuts; ++i)
        for (int j = 0; j < cuts; ++j) {
          auto point = [&](double u, double v) {
            Vec3 p;
            p[axis] = side;
            p[(axis + 1) % 3] = u / cuts;
            p[(axis + 2) % 3] = v / cuts;
            return p;
          };
          uint32_t base = static_cast<uint32_t>(many.positions.size());
          many.positions.push_back(point(i, j));
          many.positions.push_back(point(i + 1, j));
          many.positions.push_back(point(i + 1, j + 1));
          many.positions.push_back(point(i, j + 1));
          Face f;
          f.vertexCount = 4;
          for (int k = 0; k < 4; ++k) f.vertices[k] = base + uint32_t(side == 0 ? k : 3 - k);
          many.addFace(f);
        }
  Solution s = solve(many, "auto", 1.0, 1e-3);
  EXPECT_EQ(s.stats.solver, "stochastic");
  double area = 0, power = 0;
  for (size_t e = 0; e < s.elementCount(); ++e) {
    area += s.mesh.elements[e].area;
    power += s.radiosity[e].average() * s.mesh.elements[e].area;
  }
  EXPECT_NEAR(power / area, 2 * kPi, 2e-3 * 2 * kPi);  // inward faces: the furnace again
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

/// Hierarchical radiosity held at the patch level (no refinement) with a fine
/// receiver grid: the classic one-element-per-patch system with accurate
/// patch-to-patch form factors, which the closed forms below (cube, sphere,
/// plates) describe.
Solution solvePatchLevel(const Scene &scene, int receiverGrid = 64, int maxSweeps = 0) {
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 1e9;  // one element per patch
  Solution s = initialSolution(scene, buildMesh(scene, meshOptions));
  SolverOptions options;
  options.solver = "hierarchical";
  options.linkThreshold = 1.0;                              // every pair links at the root
  options.visibilitySamples = receiverGrid * receiverGrid;  // the receiver grid per link
  options.tolerance = 1e-12;
  options.maxIterations = maxSweeps;
  options.refinementRounds = 1;
  solveRadiosity(tracer, s, options);
  return s;
}

Scene unitCubeWithCeilingEmitter() {
  const int walls[6] = {0, 0, 0, 1, 0, 0};
  Scene scene = test::closedBox(1.0, walls);
  Material wall, light;
  wall.diffuse = Bands(0.5);
  light.diffuse = Bands(0.0);
  light.emission = Bands(1.0 / kPi);  // exitance E = π·L = 1
  scene.materials = {wall, light};
  return scene;
}

TEST(ClosedForm, UnitCubeJacobiConvergenceAsTabulated) {
  // From B⁰ = E, Jacobi's max error after 1, 2 and 5 sweeps is 6.7e-2, 2.7e-2
  // and 1.7e-3 (Jacobi on the cube's 6 × 6 system with the closed-form factors,
  // against its direct solve, computed in double precision). The hierarchical
  // solver held at patch level sweeps exactly like Jacobi (gather everything,
  // then push–pull). Later rows (1.8e-5 at 10) fall below the form factors'
  // quadrature error.
  const std::pair<int, double> table[] = {{1, 6.7e-2}, {2, 2.7e-2}, {5, 1.7e-3}};
  for (auto [sweeps, error] : table) {
    Solution s = solvePatchLevel(unitCubeWithCeilingEmitter(), 64, sweeps);
    double worst = 0;
    for (uint32_t e = 0; e < 6; ++e) {
      const Vec3 &n = s.mesh.normalOf(e);
      double exact = n.y > 0.5 ? 0.1666003 : (n.y < -0.5 ? 1.0 : 0.1666832);
      worst = std::max(worst, std::abs(s.radiosity[e][0] - exact));
    }
    EXPECT_NEAR(worst, error, 0.05 * error + 2e-4) << sweeps << " sweeps";  // the table has 2 digits
  }
}

TEST(ClosedForm, UnitCubeWithCeilingEmitter) {
  // The cube of docs/two-pass.md (`rushmeier`): ceiling E = 1 (ρ = 0), other
  // faces ρ = 0.5; with exact patch form factors the floor is 0.1666003 and
  // each wall 0.1666832. The 64 × 64 midpoint grid integrates the adjacent-face
  // factor (log-singular at the shared edge) to ~1e-4, which bounds the
  // tolerance.
  Solution s = solvePatchLevel(unitCubeWithCeilingEmitter());
  ASSERT_EQ(s.elementCount(), 6u);
  for (uint32_t e = 0; e < 6; ++e) {
    const Vec3 &n = s.mesh.normalOf(e);
    double expected = n.y > 0.5 ? 0.1666003 : (n.y < -0.5 ? 1.0 : 0.1666832);
    EXPECT_NEAR(s.radiosity[e][0], expected, 2e-4) << "face with normal " << n.x << " " << n.y << " " << n.z;
  }
  // Energy balance of a closed scene (docs/radiosity.md): emitted = absorbed.
  EXPECT_NEAR(s.stats.absorbedPower.average(), s.stats.emittedPower.average(), 1e-3);
}

TEST(ClosedForm, InteriorOfASphere) {
  // Inside a sphere cosθ cosθ'/(πr²) = 1/(4πR²), so every F_ij = A_j/A and,
  // whatever the emission, B_i − E_i = ρĒ/(1−ρ) with Ē the area-weighted mean
  // emission. The sphere is a 24 × 12 tessellation turned inside out, each ring
  // with its own emission (E = 1 + 0.5 cos θ); flat facets make the kernel only
  // nearly constant, and a coarse receiver grid integrates neighbouring facets
  // roughly, but with emission varying smoothly those errors cancel to within
  // 1% per facet (measured: 0.5%) and 0.2% in the mean.
  Scene scene;
  scene.objects.push_back({"sphere", "test"});
  const int segments = 24, rings = 12;
  const double rho = 0.6;
  for (int r = 0; r < rings; ++r) {
    Material m;
    m.diffuse = Bands(rho);
    m.emission = Bands((1 + 0.5 * std::cos(kPi * (r + 0.5) / rings)) / kPi);
    scene.materials.push_back(m);
  }
  for (int r = 0; r <= rings; ++r)
    for (int k = 0; k < segments; ++k) {
      double theta = kPi * r / rings, phi = 2 * kPi * k / segments;
      scene.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)});
    }
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      uint32_t a = r * segments + k, b = r * segments + (k + 1) % segments, c = a + segments, d = b + segments;
      for (auto tri : {std::array<uint32_t, 3>{a, b, d}, std::array<uint32_t, 3>{a, d, c}}) {
        Face f;
        for (int i = 0; i < 3; ++i) f.vertices[i] = tri[i];
        f.material = static_cast<uint32_t>(r);
        Vec3 n = scene.faceNormal(f),
             centroid = (scene.positions[tri[0]] + scene.positions[tri[1]] + scene.positions[tri[2]]) / 3;
        if (dot(n, centroid) > 0) std::swap(f.vertices[1], f.vertices[2]);  // face inwards
        scene.addFace(f);
      }
    }
  Solution s = solvePatchLevel(scene, 4);
  double area = 0, emitted = 0;
  for (uint32_t e = 0; e < s.elementCount(); ++e) {
    area += s.mesh.elements[e].area;
    emitted += s.emission[e][0] * s.mesh.elements[e].area;
  }
  const double expected = rho * (emitted / area) / (1 - rho);
  double reflected = 0, worst = 0;
  for (uint32_t e = 0; e < s.elementCount(); ++e) {
    double b = s.radiosity[e][0] - s.emission[e][0];
    EXPECT_NEAR(b, expected, 0.01 * expected) << "element " << e;
    worst = std::max(worst, std::abs(b - expected) / expected);
    reflected += b * s.mesh.elements[e].area;
  }
  EXPECT_NEAR(reflected / area, expected, 0.002 * expected);
  std::cout << "sphere interior: worst facet " << worst << "\n";
}

TEST(ClosedForm, TwoParallelPlates) {
  // The infinite-plate closed form for finite plates: two unit squares at
  // distance 1 exchange F = 0.1998249 (Howell C-11); B1 = E1 + ρ1 F B2 and
  // B2 = ρ2 F B1 solve in closed form. The open sides let the rest escape.
  Scene scene;
  scene.objects.push_back({"plates", "test"});
  Material emitter, receiver;
  emitter.diffuse = Bands(0.5);
  emitter.emission = Bands(1.0 / kPi);
  receiver.diffuse = Bands(0.8);
  scene.materials = {emitter, receiver};
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  test::addQuads(scene, {0, 1});  // the bottom plate, the top one
  Solution s = solvePatchLevel(scene);
  const double F = 0.1998249, E1 = 1, rho1 = 0.5, rho2 = 0.8;
  const double B1 = E1 / (1 - rho1 * rho2 * F * F), B2 = rho2 * F * B1;
  EXPECT_NEAR(s.radiosity[0][0], B1, 1e-5);
  EXPECT_NEAR(s.radiosity[1][0], B2, 1e-5);
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

TEST(Adaptive, RefiningByTheErrorEstimateImprovesTheImage) {
  // Cohen et al. 1986: split where nodes disagree with their element, solve
  // again. Each round must refine (more elements, T-vertices consistent), and
  // the interpolated image must move towards the path tracer's.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  ImageAgainstPath image{scene, tracer, 48};
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.2;
  std::vector<double> errors;
  std::vector<size_t> elements;
  for (int rounds : {0, 1, 2}) {
    SolverOptions options;
    options.solver = "gauss-seidel";
    options.adaptiveRounds = rounds;
    options.adaptiveThreshold = 0.1;
    Solution s = meshAndSolve(scene, tracer, meshOptions, options);
    for (const RadiosityMesh::TVertex &t : s.mesh.tVertices)
      ASSERT_NEAR(s.nodeRadiosity[t.node][1], 0.5 * (s.nodeRadiosity[t.edgeStart][1] + s.nodeRadiosity[t.edgeEnd][1]),
                  1e-12);
    elements.push_back(s.elementCount());
    errors.push_back(image.blockError(s));
  }
  std::cout << "adaptive rounds 0, 1, 2: elements " << elements[0] << " " << elements[1] << " " << elements[2]
            << ", block errors " << errors[0] << " " << errors[1] << " " << errors[2] << "\n";
  EXPECT_GT(elements[1], elements[0]);
  EXPECT_GT(elements[2], elements[1]);
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
}

TEST(Adaptive, HierarchicalRefusesRoundsAndTheBoundHolds) {
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.1;
  SolverOptions options;
  options.adaptiveRounds = 2;
  options.solver = "hierarchical";
  EXPECT_THROW(meshAndSolve(scene, tracer, meshOptions, options), InputError);
  options.solver = "stochastic";
  options.maxElements = 600;
  Solution s = meshAndSolve(scene, tracer, meshOptions, options);
  EXPECT_LE(s.elementCount(), 600u);
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

TEST(Mesh, NodesAreSharedAcrossASplitSurfaceButNotAcrossCreases) {
  // The Cornell left wall is 3.2 mm off planar, so the loader splits it into
  // two triangles: their nodes along the shared diagonal must carry one value
  // (no seam), while the floor and the back wall keep their own along the crease.
  Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  Solution s = solve(scene, "gauss-seidel", 0.1, 1e-4);
  std::map<std::tuple<long long, long long, long long>, std::vector<uint32_t>> at;
  for (uint32_t v = 0; v < s.mesh.nodes.size(); ++v) {
    const Vec3 &p = s.mesh.nodes[v];
    at[{std::llround(p.x * 1e5), std::llround(p.y * 1e5), std::llround(p.z * 1e5)}].push_back(v);
  }
  int seamPairs = 0, creasePairs = 0;
  for (const auto &[key, nodes] : at)
    for (size_t a = 0; a < nodes.size(); ++a)
      for (size_t b = a + 1; b < nodes.size(); ++b) {
        const Patch &pa = s.mesh.patches[s.mesh.nodePatch[nodes[a]]], &pb = s.mesh.patches[s.mesh.nodePatch[nodes[b]]];
        std::string oa = scene.objects[pa.object].name, ob = scene.objects[pb.object].name;
        if (oa == "left-wall" && ob == "left-wall") {
          ++seamPairs;
          EXPECT_DOUBLE_EQ(s.nodeRadiosity[nodes[a]][0], s.nodeRadiosity[nodes[b]][0]);
        }
        if ((oa == "floor" && ob == "back-wall") || (oa == "back-wall" && ob == "floor")) {
          ++creasePairs;
          EXPECT_NE(s.nodeRadiosity[nodes[a]][0], s.nodeRadiosity[nodes[b]][0]);
        }
      }
  EXPECT_GT(seamPairs, 2);
  EXPECT_GT(creasePairs, 2);
}

}  // namespace
}  // namespace radiant
