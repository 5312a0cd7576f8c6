// Diffuse transmission (Material::transmittance, MGF `td`): the BSDF's
// transmission lobe, and every solver's B = E + ρH + τH' (radiosity/transmission.h)
// against closed-form balances and the path tracer.
#include <gtest/gtest.h>

#include <cmath>

#include "path_image_comparison.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "render/bsdf.h"
#include "scene/load_scene.h"
#include "test_scenes.h"
#include "util/error.h"
#include "util/sampling.h"

namespace radiant {
namespace {

const char *const kSolvers[] = {"gauss-seidel", "progressive", "hierarchical", "hierarchical-exact", "stochastic"};

/// Tolerances of PointLight.EverySolverMeetsTheInterreflectionFormulaInAPointLitRoom:
/// collocation and the stochastic solver's noise 1 %, the Galerkin solvers 0.3 %.
double formulaTolerance(const std::string &solver) {
  return solver == "stochastic" || solver == "gauss-seidel" || solver == "progressive" ? 0.01 : 0.003;
}

TEST(Translucency, TheBsdfScattersRhoPlusTauAndTransmitsTau) {
  Material m;
  m.diffuse = Bands(0.5, 0.4, 0.3);
  m.transmittance = Bands(0.2, 0.3, 0.1);
  const Vec3 n{0, 0, 1}, wo = normalize(Vec3{0.3, -0.2, 1});
  const Bsdf bsdf(m, n, n, wo);
  // A direction through the surface: τ/π, with the transmission lobe's density.
  const Vec3 through = normalize(Vec3{0.1, 0.4, -1});
  EXPECT_NEAR(bsdf.evaluate(through)[1], 0.3 / kPi, 1e-12);
  const double pTransmit = 0.2 / (0.2 + 0.4);  // band averages of τ and ρ
  EXPECT_NEAR(bsdf.pdf(through), pTransmit * std::abs(through.z) / kPi, 1e-12);
  EXPECT_NEAR(bsdf.evaluate(normalize(Vec3{0.1, 0.4, 1}))[1], 0.4 / kPi, 1e-12);
  // E[weight] is the albedo ρ + τ, and its transmitted part τ, per band.
  const int count = 200000;
  Bands all(0.0), transmitted(0.0), allSquares(0.0);
  Pcg32 rng(3, 0);
  for (int i = 0; i < count; ++i) {
    BsdfSample s;
    if (!bsdf.sample(rng.next(), rng.next(), rng.next(), s)) continue;
    EXPECT_EQ(s.isTransmission, s.wi.z < 0);
    all += s.weight;
    allSquares += s.weight * s.weight;
    if (s.isTransmission) transmitted += s.weight;
  }
  for (int b = 0; b < kBandCount; ++b) {
    const double mean = all[b] / count;
    const double standardError = std::sqrt((allSquares[b] / count - mean * mean) / count);
    EXPECT_NEAR(mean, m.diffuse[b] + m.transmittance[b], 4 * standardError + 1e-12) << b;
    EXPECT_NEAR(transmitted[b] / count, m.transmittance[b], 4 * standardError + 1e-12) << b;
  }
  // Seen from the far side, light from the near side: the same lobe, reciprocal.
  const Bsdf fromBelow(m, n, n, through);
  EXPECT_NEAR(fromBelow.evaluate(wo)[2], bsdf.evaluate(through)[2], 1e-15);
}

/// The closed point-lit room of two_sided_test with a free-standing panel of
/// reflectance 0.3 and diffuse transmittance 0.3: every surface scatters 0.6.
Scene roomWithTranslucentPanel() {
  Material wall;
  wall.name = "wall";
  wall.diffuse = Bands(0.6);
  Scene scene = test::pointLitRoom(wall);
  Material panel;
  panel.name = "paper";
  panel.diffuse = Bands(0.3);
  panel.transmittance = Bands(0.3);
  panel.twoSided = true;
  scene.materials.push_back(panel);
  test::addQuad(scene, {{2.6, 0.4, 0.6}, {2.6, 2.2, 0.6}, {2.6, 2.2, 2.2}, {2.6, 0.4, 2.2}}, 1);
  scene.addBackFaces();
  return scene;
}

TEST(Translucency, EverySolverMeetsTheInterreflectionFormulaWithATranslucentPanel) {
  // Every surface absorbs 1 − 0.6 of its irradiance (the panel: 1 − ρ − τ),
  // so the area mean is Φ / (A (1 − 0.6)), both sides of the panel counted.
  // The lamp lights the panel's back (face 7); its front (face 6) gets τ of
  // that straight through, more than the room reflects onto it.
  const Scene scene = roomWithTranslucentPanel();
  const double area = 2 * (4 * 2.5 + 4 * 3 + 3 * 2.5) + 2 * 1.8 * 1.6;
  const double flux = scene.lights[0].power()[0];
  const double expected = flux / (area * (1 - 0.6));
  RayTracer tracer(scene);
  for (const char *solver : kSolvers) {
    MeshOptions mesh;
    mesh.maxEdgeLength = 0.5;
    SolverOptions options;
    options.solver = solver;
    options.tolerance = 1e-5;
    const Solution s = meshAndSolve(scene, tracer, mesh, options);
    double sum = 0, total = 0, direct = 0, frontRadiosity = 0, frontIrradiance = 0, frontArea = 0;
    for (size_t e = 0; e < s.elementCount(); ++e) {
      const double a = s.mesh.elements[e].area;
      sum += s.irradiance[e][0] * a;
      direct += s.direct[e][0] * a;
      total += a;
      if (s.mesh.patchOf(uint32_t(e)).face == 6)
        frontRadiosity += s.radiosity[e][0] * a, frontIrradiance += s.irradiance[e][0] * a, frontArea += a;
    }
    ASSERT_NEAR(total, area, 1e-9 * area) << solver;
    EXPECT_NEAR(sum / total / expected, 1.0, formulaTolerance(solver)) << solver;
    // The ratios docs/radiosity.md quotes (--gtest_output=xml:FILE shows them).
    RecordProperty(std::string(solver) + "-formula", std::to_string(sum / total / expected));
    // Each watt of the lamp is scattered once as direct light: 0.6 Φ (ρ of
    // the walls, ρ + τ of the panel: the two sides share it).
    EXPECT_NEAR(direct / (0.6 * flux), 1.0, 0.003) << solver;
    // The front's radiosity: ρ of its own irradiance plus what came through.
    EXPECT_GT(frontRadiosity - 0.3 * frontIrradiance, 0.5 * 0.3 * frontIrradiance) << solver;
    EXPECT_NEAR(s.stats.absorbedPower[0] / flux, 1.0, formulaTolerance(solver)) << solver;
  }
}

/// Two closed rooms side by side, x ∈ [0, 2] and [2, 4], sharing the wall at
/// x = 2: two faces back to back (paired by Scene::addBackFaces), translucent
/// (ρ = 0.4 like the walls, τ = 0.3). A point light in the first room only.
Scene twoRoomsThroughAWall() {
  Scene scene;
  const int walls[6] = {0, 1, 0, 0, 0, 0};  // the first room's wall at x = 2 is translucent
  Scene first = test::closedBox(1.0, walls);
  const int otherWalls[6] = {1, 0, 0, 0, 0, 0};  // the second's at x = 2 (its x = 0)
  Scene second = test::closedBox(1.0, otherWalls);
  scene.objects.push_back({"rooms", "test"});
  for (Vec3 p : first.positions) scene.positions.push_back(Vec3{p.x * 2, p.y * 2.5, p.z * 3});
  for (Vec3 p : second.positions) scene.positions.push_back(Vec3{2 + p.x * 2, p.y * 2.5, p.z * 3});
  Material wall;
  wall.name = "wall";
  wall.diffuse = Bands(0.4);
  Material divider = wall;
  divider.name = "divider";
  divider.transmittance = Bands(0.3);
  divider.twoSided = true;
  scene.materials = {wall, divider};
  for (Face f : first.faces) scene.addFace(f);
  for (Face f : second.faces) {
    for (uint32_t &v : f.vertices) v += uint32_t(first.positions.size());
    scene.addFace(f);
  }
  scene.addBackFaces();
  PointLight light;
  light.name = "bulb";
  light.position = Vec3{0.8, 1.6, 1.2};
  light.candela = 1000;
  scene.lights.push_back(light);
  return scene;
}

TEST(Translucency, TheSecondRoomGetsExactlyWhatTheWallPassesThrough) {
  // The second room is closed: what enters it is τ H₁ A through the wall (H₁
  // the irradiance on the first room's side), and what leaves its light is
  // 1 − ρ of every irradiance there, since ρ is 0.4 on every surface of that
  // room (on the wall's side 1 − ρ is what it absorbs and what it passes
  // back to the first room):
  //   (1 − ρ) Σ_room 2 H A = τ H₁ A_wall.
  // Nothing reaches the second room otherwise.
  const Scene scene = twoRoomsThroughAWall();
  ASSERT_EQ(scene.faces.size(), 12u);
  ASSERT_EQ(scene.faces[1].twin, 6);
  RayTracer tracer(scene);
  for (const char *solver : kSolvers) {
    MeshOptions mesh;
    mesh.maxEdgeLength = 0.5;
    SolverOptions options;
    options.solver = solver;
    options.tolerance = 1e-5;
    const Solution s = meshAndSolve(scene, tracer, mesh, options);
    double secondRoom = 0, wallFirst = 0, wallArea = 0;
    for (size_t e = 0; e < s.elementCount(); ++e) {
      const double a = s.mesh.elements[e].area;
      const uint32_t face = s.mesh.patchOf(uint32_t(e)).face;
      if (face >= 6) secondRoom += s.irradiance[e][0] * a;
      if (face == 1) wallFirst += s.irradiance[e][0] * a, wallArea += a;
    }
    ASSERT_NEAR(wallArea, 2.5 * 3, 1e-9) << solver;
    ASSERT_GT(secondRoom, 0) << solver;
    EXPECT_NEAR(0.6 * secondRoom / (0.3 * wallFirst), 1.0, formulaTolerance(solver)) << solver;
    RecordProperty(std::string(solver) + "-balance", std::to_string(0.6 * secondRoom / (0.3 * wallFirst)));
  }
}

TEST(Translucency, TheLightThroughLandsWhereItBelongsWhenTheSidesAreMeshedApart) {
  // The first room's side of the wall split once more than the second's
  // (as adaptive rounds split each side by its own error): each element of
  // the second side takes the mean over the four finer ones under it, not
  // one of them, and the balance of the second room holds for every solver
  // on that fixed mesh.
  const Scene scene = twoRoomsThroughAWall();
  RayTracer tracer(scene);
  MeshOptions meshOptions;
  meshOptions.maxEdgeLength = 0.5;
  RadiosityMesh mesh = buildTreeMesh(scene, meshOptions);
  for (int round = 0; round < 1; ++round) {
    std::vector<double> error(mesh.elements.size(), 0.0);
    for (size_t e = 0; e < mesh.elements.size(); ++e) error[e] = mesh.patchOf(uint32_t(e)).face == 1 ? 1.0 : 0.0;
    ASSERT_GT(refineMesh(mesh, error, 0.5, 100000), 0u);
  }
  for (const char *solver : {"gauss-seidel", "progressive", "stochastic"}) {
    Solution s = initialSolution(scene, mesh);
    SolverOptions options;
    options.solver = solver;
    options.tolerance = 1e-5;
    solveRadiosity(tracer, s, options);
    size_t first = 0, second = 0;
    double secondRoom = 0, wallFirst = 0;
    for (size_t e = 0; e < s.elementCount(); ++e) {
      const double a = s.mesh.elements[e].area;
      const uint32_t face = s.mesh.patchOf(uint32_t(e)).face;
      if (face >= 6) secondRoom += s.irradiance[e][0] * a;
      if (face == 1) wallFirst += s.irradiance[e][0] * a, ++first;
      if (face == 6) ++second;
    }
    ASSERT_EQ(first, 4 * second) << solver;
    EXPECT_NEAR(0.6 * secondRoom / (0.3 * wallFirst), 1.0, formulaTolerance(solver)) << solver;
    // The other way, each of the four finer elements gets τ times the H of
    // the coarse one over it: B − ρH = τH' everywhere, not four times that
    // in one of them and nothing in the rest.
    for (size_t e = 0; e < s.elementCount(); ++e) {
      if (s.mesh.patchOf(uint32_t(e)).face != 1) continue;
      const uint32_t over = s.mesh.locate(6, s.mesh.elements[e].centre).element;
      const double through = s.radiosity[e][0] - 0.4 * s.irradiance[e][0];
      EXPECT_NEAR(through, 0.3 * s.irradiance[over][0], 1e-3 * 0.3 * s.irradiance[over][0]) << solver << " " << e;
    }
  }
}

TEST(Translucency, InterpolatedRadiosityMatchesThePathTracerBehindTheWall) {
  // The camera in the second room looks at the translucent wall: everything
  // it sees came through it. hierarchical-exact's interpolated image against
  // the path tracer, region by region, within the noise.
  const Scene scene = twoRoomsThroughAWall();
  CameraSettings camera;
  camera.eye = {3.6, 1.25, 1.5};
  camera.target = {2, 1.25, 1.5};
  camera.up = {0, 1, 0};
  camera.verticalFovDegrees = 80;
  const int size = 32;
  const Film path = test::pathTraced(scene, camera, size, 256, 5);
  RayTracer tracer(scene);
  MeshOptions mesh;
  SolverOptions options;
  const Solution solution = meshAndSolve(scene, tracer, mesh, options);
  RenderContext context;
  context.solution = &solution;
  Film interpolated(size, size);
  DriverOptions driver;
  driver.samplesPerPixel = 16;
  driver.stopConvergedPixels = false;
  renderImage(PinholeCamera(camera, size, size), *createRenderer("interpolate", tracer, context), driver, interpolated);
  for (int y = 0; y < size; y += 16)
    for (int x = 0; x < size; x += 16) {
      const test::RegionSums sums = test::regionSums(interpolated, path, x, y, 16, 16);
      ASSERT_GT(sums.b, 0);
      // 4 σ of the noise, plus 2 % for the interpolation of a diffuse field on the solver's mesh.
      EXPECT_NEAR(sums.a, sums.b, 4 * std::sqrt(sums.variance) + 0.02 * sums.b) << x << "," << y;
    }
}

TEST(Translucency, MaterialsSayDiffuseTransmittance) {
  auto scene = [](const std::string &material) {
    return R"({"camera": {"eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0]},
      "materials": {"paper": )" +
           material + R"(},
      "objects": [{"name": "sheet", "type": "quad", "material": "paper",
                   "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}]})";
  };
  const Scene translucent =
      parseSceneJson(scene(R"({"reflectance": 0.5, "diffuse_transmittance": [0.3, 0.2, 0.1]})"), "t.json");
  EXPECT_TRUE(translucent.materials[0].twoSided);
  EXPECT_NEAR(translucent.materials[0].transmittance[1], 0.2, 1e-12);
  ASSERT_EQ(translucent.faces.size(), 2u);  // two-sided: light goes through to the back
  auto refused = [&](const std::string &material, const std::string &path, const std::string &words) {
    try {
      parseSceneJson(scene(material), "bad.json");
      ADD_FAILURE() << material << " accepted";
    } catch (const InputError &e) {
      EXPECT_EQ(e.location().jsonPath, path) << e.what();
      EXPECT_NE(e.message().find(words), std::string::npos) << e.message();
    }
  };
  refused(R"({"reflectance": 0.6, "diffuse_transmittance": 0.4})", "/materials/paper", "reaches 1");
  refused(R"({"reflectance": 0.2, "diffuse_transmittance": -0.1})", "/materials/paper/diffuse_transmittance",
          "negative");
  refused(R"({"reflectance": 0.2, "diffuse_transmittance": 0.3, "two_sided": false})", "/materials/paper/two_sided",
          "two-sided");
  refused(R"({"type": "mirror", "diffuse_transmittance": 0.3})", "/materials/paper/diffuse_transmittance",
          "does not apply");
}

TEST(Translucency, BothSidesOfASurfaceHaveOneTransmittance) {
  // Two faces back to back (one surface) of materials with different τ: refused.
  const std::string text = R"({"camera": {"eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0]},
    "materials": {"a": {"reflectance": 0.5, "diffuse_transmittance": 0.3},
                  "b": {"reflectance": 0.5, "diffuse_transmittance": 0.2}},
    "objects": [{"name": "front", "type": "quad", "material": "a",
                 "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]},
                {"name": "back", "type": "quad", "material": "b",
                 "vertices": [[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]]}]})";
  try {
    parseSceneJson(text, "sides.json");
    FAIL() << "accepted";
  } catch (const InputError &e) {
    EXPECT_NE(e.message().find("the two sides of one surface"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace radiant
