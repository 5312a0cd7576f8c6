// Calculation grids (scene "grids", radiosity/calculation_grid.h): parsing
// with errors at their JSON paths, and the illuminance measured on them
// against closed forms (docs/validation.md).
#include "radiosity/calculation_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "display/grid_plan.h"
#include "radiosity/solver.h"
#include "scene/load_scene.h"
#include "test_scenes.h"

namespace radiant {
namespace {

std::string withGrids(const std::string &grids, const std::string &units = "metres") {
  return R"({"units": ")" + units + R"(", "materials": {"lamp": {"reflectance": 0, "emission": 1}},
    "objects": [{"type": "quad", "material": "lamp", "vertices": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]]}],
    "grids": )" +
         grids + "}";
}

TEST(CalculationGridParsing, PointsAreCellCentresInMetres) {
  Scene s = parseSceneJson(
      withGrids(R"([{"name": "desk", "origin": [0, 0, 0], "u": [100, 0, 0], "v": [0, 0, 50], "nu": 4, "nv": 2}])",
                "centimetres"),
      "g.json");
  ASSERT_EQ(s.grids.size(), 1u);
  const CalculationGrid &g = s.grids[0];
  EXPECT_EQ(g.name, "desk");
  EXPECT_EQ(g.pointCount(), 8u);
  const Vec3 p = g.point(0, 0), q = g.point(3, 1);
  EXPECT_NEAR(p.x, 0.125, 1e-12);
  EXPECT_NEAR(p.z, 0.125, 1e-12);
  EXPECT_NEAR(q.x, 0.875, 1e-12);
  EXPECT_NEAR(q.z, 0.375, 1e-12);
  // Default normal u × v: x × z = −y.
  EXPECT_NEAR(g.normal.y, -1, 1e-12);
}

TEST(CalculationGridParsing, GivenNormalIsNormalisedAndNamesDefault) {
  Scene s =
      parseSceneJson(withGrids(R"([{"origin": [0,0,0], "u": [1,0,0], "v": [0,0,1], "normal": [0, 2, 0]}])"), "g.json");
  ASSERT_EQ(s.grids.size(), 1u);
  EXPECT_EQ(s.grids[0].name, "grid-0");
  EXPECT_EQ(s.grids[0].nu, 1);
  EXPECT_NEAR(s.grids[0].normal.y, 1, 1e-12);
}

TEST(CalculationGridParsing, ErrorsNameTheirJsonPath) {
  struct Row {
    const char *grids, *path, *words;
  };
  const Row rows[] = {
      {R"([{"origin": [0,0,0], "u": [1,0,0], "v": [2,0,0]}])", "/grids/0/v", "no area"},
      {R"([{"origin": [0,0,0], "u": [1,0,0], "v": [0,0,1], "nu": 0}])", "/grids/0/nu", ""},
      {R"([{"origin": [0,0,0], "u": [1,0,0], "v": [0,0,1], "nu": 2000, "nv": 2000}])", "/grids/0/nv", "allowed"},
      {R"([{"origin": [0,0,0], "u": [1,0,0], "v": [0,0,1], "normal": [0,0,0]}])", "/grids/0/normal", "zero"},
      {R"([{"origin": [0,0,0], "u": [1,0,0], "v": [0,0,1], "nuu": 3}])", "/grids/0", "nuu"},
      {R"([{"u": [1,0,0], "v": [0,0,1]}])", "/grids/0", "origin"},
      {R"([{"name": "a", "origin": [0,0,0], "u": [1,0,0], "v": [0,0,1]},
           {"name": "a", "origin": [0,0,0], "u": [1,0,0], "v": [0,0,1]}])",
       "/grids/1/name", "second"},
      {R"({"name": "a"})", "/grids", ""},
  };
  for (const Row &row : rows) {
    try {
      parseSceneJson(withGrids(row.grids), "g.json");
      ADD_FAILURE() << "accepted " << row.grids;
    } catch (const InputError &e) {
      EXPECT_EQ(e.location().jsonPath.rfind(row.path, 0), 0u) << e.what() << " for " << row.grids;
      EXPECT_NE(std::string(e.what()).find(row.words), std::string::npos) << e.what();
    }
  }
}

Solution solve(const Scene &scene, const RayTracer &tracer, double meshSize) {
  MeshOptions mesh;
  mesh.maxEdgeLength = meshSize;
  SolverOptions solver;
  solver.solver = "gauss-seidel";
  solver.tolerance = 1e-8;
  return meshAndSolve(scene, tracer, mesh, solver);
}

/// F from a point to a parallel a × b rectangle at height h, the point below
/// one of its corners (C&W appendix; Howell's catalogue C-11).
double formFactorBelowCorner(double a, double b, double h) {
  const double x = a / h, y = b / h;
  return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
         (2 * kPi);
}

// Validation 1 (docs/validation.md): a 2 m × 1 m Lambertian emitter of
// radiance L = 1 W·sr⁻¹·m⁻² at 1.5 m above a black floor; a grid of three
// points on the floor below its centre, a corner and outside it. E = π L F.
const char *kRectangleScene = R"({"units": "metres",
  "materials": {"lamp": {"reflectance": 0, "emission": 1}, "black": {"reflectance": 0}},
  "objects": [
    {"name": "lamp", "type": "quad", "material": "lamp", "vertices": [[0,1.5,0],[2,1.5,0],[2,1.5,1],[0,1.5,1]]},
    {"name": "floor", "type": "quad", "material": "black", "vertices": [[-2,0,-2],[-2,0,3],[4,0,3],[4,0,-2]]}],
  "grids": [{"name": "floor", "origin": [-1, 0, -0.5], "u": [3, 0, 0], "v": [0, 0, 1], "nu": 3, "nv": 1,
             "normal": [0, 1, 0]}]})";

TEST(CalculationGridIlluminance, BelowARectangularEmitterItIsPiLTimesTheFormFactor) {
  Scene scene = parseSceneJson(kRectangleScene, "rectangle.json");
  RayTracer tracer(scene);
  Solution solution = solve(scene, tracer, 0.5);
  GridOptions options;
  std::vector<GridIlluminance> grids = computeGridIlluminance(scene, tracer, {&solution, 1}, options);
  ASSERT_EQ(grids.size(), 1u);
  // Points at x = −0.5 (0.5 m outside the lamp's edge), 0.5, 1.5 and z = 0.
  // F of a point not below the rectangle: the difference of two corner forms.
  const double h = 1.5;
  const double expected[3] = {
      formFactorBelowCorner(2.5, 1, h) - formFactorBelowCorner(0.5, 1, h),  // z = 0 is the lamp's edge
      formFactorBelowCorner(0.5, 1, h) + formFactorBelowCorner(1.5, 1, h),
      formFactorBelowCorner(1.5, 1, h) + formFactorBelowCorner(0.5, 1, h),
  };
  for (int i = 0; i < 3; ++i) {
    const GridPointIlluminance &p = grids[0].at(i, 0);
    const double lux = kLuminousEfficacy * kPi * expected[i];  // L = 1 in every band: Y = 1
    EXPECT_NEAR(p.illuminanceLux, lux, 1e-6 * lux) << "point " << i;
    EXPECT_NEAR(p.indirectLux, 0, 1e-12);
  }
}

// Validation 2: the closed diffuse room (the furnace), every wall emitting
// and reflecting ρ: Φ = π L_e A and E = Φ/(A(1 − ρ)) at every point facing
// any way, so also the average over any grid.
TEST(CalculationGridIlluminance, InAClosedDiffuseRoomItIsTheInterreflectionFormula) {
  Scene scene = test::furnace(1.0, 0.5);
  CalculationGrid grid;
  grid.name = "middle";
  grid.origin = {0.1, 0.5, 0.1};
  grid.u = {0.8, 0, 0};
  grid.v = {0, 0, 0.8};
  grid.normal = {0, 1, 0};
  grid.nu = grid.nv = 4;
  scene.grids.push_back(grid);
  grid.name = "wall";
  grid.origin = {0, 0.1, 0.1};
  grid.u = {0, 0.8, 0};
  grid.normal = {1, 0, 0};
  scene.grids.push_back(grid);
  RayTracer tracer(scene);
  Solution solution = solve(scene, tracer, 0.25);
  GridOptions options;
  const std::vector<GridIlluminance> grids = computeGridIlluminance(scene, tracer, {&solution, 1}, options);
  const double expected = kLuminousEfficacy * kPi * 1.0 / (1 - 0.5);
  for (const GridIlluminance &g : grids) {
    EXPECT_NEAR(g.averageLux, expected, 1e-3 * expected) << g.grid.name;
    for (const GridPointIlluminance &p : g.points) {
      EXPECT_NEAR(p.illuminanceLux, expected, std::max(4 * p.standardErrorLux, 1e-6 * expected));
      EXPECT_LE(p.standardErrorLux, 0.005 * p.illuminanceLux);
    }
    EXPECT_NEAR(g.uniformity(), 1, 1e-3);
  }
}

// A room lit by one emitter: the standard error the gather reports is its
// real scatter (two seeds differ by about √2 σ), and the result does not
// depend on the thread count.
TEST(CalculationGridIlluminance, DeterministicAcrossThreadsAndHonestStandardError) {
  const int walls[6] = {0, 0, 0, 1, 0, 0};
  Scene scene = test::closedBox(1.0, walls);
  Material wall;
  wall.name = "wall";
  wall.diffuse = Bands(0.6);
  Material lamp;
  lamp.name = "lamp";
  lamp.diffuse = Bands(0.0);
  lamp.emission = Bands(5.0);
  scene.materials = {wall, lamp};
  CalculationGrid grid;
  grid.name = "floor";
  grid.origin = {0, 0, 0};
  grid.u = {1, 0, 0};
  grid.v = {0, 0, 1};
  grid.normal = {0, 1, 0};
  grid.nu = grid.nv = 5;
  scene.grids.push_back(grid);
  RayTracer tracer(scene);
  Solution solution = solve(scene, tracer, 0.25);
  GridOptions options;
  options.maxSamples = options.minSamples = 1024;
  options.threads = 1;
  const auto one = computeGridIlluminance(scene, tracer, {&solution, 1}, options);
  options.threads = 4;
  const auto four = computeGridIlluminance(scene, tracer, {&solution, 1}, options);
  options.seed = 2;
  const auto other = computeGridIlluminance(scene, tracer, {&solution, 1}, options);
  double chiSquare = 0;
  for (size_t k = 0; k < one[0].points.size(); ++k) {
    EXPECT_EQ(one[0].points[k].illuminanceLux, four[0].points[k].illuminanceLux);
    EXPECT_GT(one[0].points[k].indirectLux, 0);
    EXPECT_GT(one[0].points[k].standardErrorLux, 0);
    const double d = one[0].points[k].illuminanceLux - other[0].points[k].illuminanceLux;
    const double s2 = std::pow(one[0].points[k].standardErrorLux, 2) + std::pow(other[0].points[k].standardErrorLux, 2);
    chiSquare += d * d / s2;
  }
  // 25 degrees of freedom: 99.9 % of χ² lies in [8, 60].
  EXPECT_GT(chiSquare, 8);
  EXPECT_LT(chiSquare, 60);
}

TEST(CalculationGridReport, CsvHasTheColumnsAndTheSummary) {
  Scene scene = parseSceneJson(kRectangleScene, "rectangle.json");
  RayTracer tracer(scene);
  Solution solution = solve(scene, tracer, 0.5);
  const auto grids = computeGridIlluminance(scene, tracer, {&solution, 1}, GridOptions{});
  const std::string path = (std::filesystem::temp_directory_path() / "radiant_grid_report_test.csv").string();
  writeGridReport(grids, 0.01, path);  // reported in centimetres
  std::ifstream in(path);
  std::string header, row;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("grid,i,j,x,y,z,illuminance_lux,standard_error_lux", 0), 0u) << header;
  std::getline(in, row);
  EXPECT_EQ(row.rfind("floor,0,0,-50,0,0,", 0), 0u) << row;
  std::getline(in, row);
  std::getline(in, row);
  std::string summary;
  std::getline(in, summary);
  const GridIlluminance &g = grids[0];
  EXPECT_NEAR(g.minimumLux, g.at(0, 0).illuminanceLux, 1e-9);
  EXPECT_NEAR(g.uniformity(), g.minimumLux / g.averageLux, 1e-12);
  EXPECT_EQ(summary.rfind("# grid floor: points 3 E_min_lux ", 0), 0u) << summary;
  EXPECT_NE(summary.find(" U0 "), std::string::npos);
  EXPECT_NE(summary.find(" Ud "), std::string::npos);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace radiant

namespace radiant {
namespace {

// The plan: a ramp along u draws its contours as vertical lines at the
// level's place, and prints the values when the cells are wide enough.
TEST(GridPlan, ContoursOfARampAreWhereTheLevelIs) {
  const int nu = 4, nv = 3;
  std::vector<double> lux;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) lux.push_back(100.0 * i);  // 0 … 300 lx
  const GridPlan plan = gridPlan(lux, nu, nv);
  EXPECT_TRUE(plan.valuesPrinted);
  EXPECT_GT(plan.width, nu * plan.cellPixels);  // the legend on the right
  EXPECT_EQ(plan.height, nv * plan.cellPixels);
  ASSERT_FALSE(plan.contourLevels.empty());
  EXPECT_EQ(plan.contourLevels.front(), 50);
  // Level 150 lies halfway between points 1 and 2: x = 2c, in every row between the points' centres.
  const int c = plan.cellPixels, x = 2 * c, y = c;  // between rows j = 1 and j = 2 of points
  bool ink = false;
  for (int dx = -1; dx <= 1; ++dx) {
    const unsigned char *p = &plan.rgb[(size_t(y) * plan.width + size_t(x + dx)) * 3];
    ink = ink || (p[0] == 0 && p[1] == 0 && p[2] == 0);
  }
  EXPECT_TRUE(ink);
  // Many small cells: no values printed.
  EXPECT_FALSE(gridPlan(std::vector<double>(1000, 5.0), 1000, 1).valuesPrinted);
}

}  // namespace
}  // namespace radiant
