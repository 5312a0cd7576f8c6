// Two-sided surfaces (Material::twoSided, MGF `sides 2`): each face of such a
// material gets a back (Scene::addBackFaces) that is a patch of its own; the
// ray tracer reports a hit from behind as a hit on the back.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "scene/load_scene.h"
#include "test_scenes.h"
#include "util/error.h"

namespace radiant {
namespace {

/// One quad in the plane z = 0, front +z, of a two-sided material.
Scene twoSidedQuad() {
  Scene scene;
  scene.objects.push_back({"sheet", "test"});
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  Material m;
  m.name = "paper";
  m.twoSided = true;
  scene.materials.push_back(m);
  Face f;
  f.vertexCount = 4;
  for (uint32_t k = 0; k < 4; ++k) f.vertices[k] = k;
  scene.addFace(f);
  scene.addBackFaces();
  return scene;
}

TEST(TwoSided, ABackFaceIsAddedAndTheTracerReportsTheSideARayMeets) {
  const Scene scene = twoSidedQuad();
  ASSERT_EQ(scene.faces.size(), 2u);
  EXPECT_EQ(scene.faces[0].twin, 1);
  EXPECT_EQ(scene.faces[1].twin, 0);
  EXPECT_FALSE(scene.faces[0].back);
  EXPECT_TRUE(scene.faces[1].back);
  EXPECT_EQ(scene.geometricFace(1), 0u);
  EXPECT_NEAR(scene.faceNormal(scene.faces[1]).z, -1.0, 1e-12);

  RayTracer tracer(scene);
  const Vec3 target{0.3, 0.7, 0};
  Hit hit;
  ASSERT_TRUE(tracer.intersect(Ray{Vec3{0.3, 0.7, 1}, Vec3{0, 0, -1}}, hit));
  EXPECT_EQ(hit.face, 0u);
  EXPECT_NEAR(hit.geometricNormal.z, 1.0, 1e-12);
  EXPECT_NEAR(length(hit.position - target), 0.0, 1e-6);
  ASSERT_TRUE(tracer.intersect(Ray{Vec3{0.3, 0.7, -1}, Vec3{0, 0, 1}}, hit));
  EXPECT_EQ(hit.face, 1u);
  EXPECT_EQ(scene.triangles[hit.triangle].face, 1u);
  EXPECT_NEAR(hit.geometricNormal.z, -1.0, 1e-12);
  EXPECT_NEAR(length(hit.position - target), 0.0, 1e-6);  // the back's own barycentrics
  // Both sides block, once.
  EXPECT_TRUE(tracer.occluded(Ray{Vec3{0.3, 0.7, 1}, Vec3{0, 0, -1}}, 2.0));
  EXPECT_TRUE(tracer.occluded(Ray{Vec3{0.3, 0.7, -1}, Vec3{0, 0, 1}}, 2.0));

  // The stream query resolves the side the same way.
  const Ray rays[2] = {{Vec3{0.6, 0.2, 1}, Vec3{0, 0, -1}}, {Vec3{0.6, 0.2, -1}, Vec3{0, 0, 1}}};
  Hit hits[2];
  uint8_t found[2] = {0, 0};
  tracer.intersectMany(rays, hits, found);
  ASSERT_TRUE(found[0] && found[1]);
  EXPECT_EQ(hits[0].face, 0u);
  EXPECT_EQ(hits[1].face, 1u);
  EXPECT_NEAR(length(hits[1].position - Vec3{0.6, 0.2, 0}), 0.0, 1e-6);
}

TEST(TwoSided, FacesAlreadyBackToBackArePairedNotDoubled) {
  // A modeller's two-sided sheet: the same corners listed both ways (one of
  // them starting elsewhere, so its fan takes the other diagonal).
  Scene scene;
  scene.objects.push_back({"sheet", "test"});
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  scene.materials.push_back(Material{});
  Face front, back;
  front.vertexCount = back.vertexCount = 4;
  const uint32_t frontOrder[4] = {0, 1, 2, 3}, backOrder[4] = {1, 0, 3, 2};
  for (int k = 0; k < 4; ++k) front.vertices[k] = frontOrder[k], back.vertices[k] = backOrder[k];
  scene.addFace(front);
  scene.addFace(back);
  scene.addBackFaces();
  ASSERT_EQ(scene.faces.size(), 2u);
  EXPECT_EQ(scene.faces[0].twin, 1);
  EXPECT_TRUE(scene.faces[1].back);
  RayTracer tracer(scene);
  Hit hit;
  // Points on both sides of the diagonal 0–2 (the back's fan cuts along 1–3).
  for (const Vec3 &p : {Vec3{0.8, 0.1, 0}, Vec3{0.1, 0.8, 0}, Vec3{0.9, 0.8, 0}}) {
    ASSERT_TRUE(tracer.intersect(Ray{p + Vec3{0, 0, -1}, Vec3{0, 0, 1}}, hit));
    EXPECT_EQ(hit.face, 1u);
    EXPECT_NEAR(length(hit.position - p), 0.0, 1e-6);
    ASSERT_TRUE(tracer.intersect(Ray{p + Vec3{0, 0, 1}, Vec3{0, 0, -1}}, hit));
    EXPECT_EQ(hit.face, 0u);
  }
}

/// test::pointLitRoom (walls of one reflectance ρ, an
/// isotropic point source) with a free-standing panel in it, 1.6 × 1.8 m,
/// its front facing away from the lamp.
Scene roomWithPanel(double rho, bool twoSidedPanel) {
  Material wall;
  wall.name = "wall";
  wall.diffuse = Bands(rho);
  Scene scene = test::pointLitRoom(wall);
  Material panel = wall;
  panel.name = "panel";
  panel.twoSided = twoSidedPanel;
  scene.materials.push_back(panel);
  // x = 2.6, front +x (the lamp is at x = 1.3).
  test::addQuad(scene, {{2.6, 0.4, 0.6}, {2.6, 2.2, 0.6}, {2.6, 2.2, 2.2}, {2.6, 0.4, 2.2}}, 1);
  scene.addBackFaces();
  return scene;
}

TEST(TwoSided, EverySolverMeetsTheInterreflectionFormulaWithAFreeStandingPanel) {
  // All light is absorbed in the end, (1 − ρ) of every irradiance, so the
  // area-mean irradiance over every surface — both sides of the panel
  // counted — is Φ / (A (1 − ρ)) exactly. With a one-sided panel its back
  // (facing the lamp) absorbs everything and the mean falls 16 % short.
  const double rho = 0.6;
  const Scene scene = roomWithPanel(rho, true);
  const double panelArea = 1.8 * 1.6;
  const double area = 2 * (4 * 2.5 + 4 * 3 + 3 * 2.5) + 2 * panelArea;
  const double flux = scene.lights[0].power()[0];
  const double expected = flux / (area * (1 - rho));
  RayTracer tracer(scene);
  for (const char *solver : {"gauss-seidel", "progressive", "hierarchical", "hierarchical-exact", "stochastic"}) {
    MeshOptions mesh;
    mesh.maxEdgeLength = 0.5;
    SolverOptions options;
    options.solver = solver;
    options.tolerance = 1e-5;
    Solution s = meshAndSolve(scene, tracer, mesh, options);
    double sum = 0, total = 0, direct = 0, front = 0, back = 0;
    for (size_t e = 0; e < s.elementCount(); ++e) {
      const double a = s.mesh.elements[e].area;
      sum += s.irradiance[e][0] * a;
      direct += s.direct[e][0] * a;
      total += a;
      const uint32_t face = s.mesh.patchOf(uint32_t(e)).face;
      if (face == 6) front += s.irradiance[e][0] * a;
      if (face == 7) back += s.irradiance[e][0] * a;
    }
    ASSERT_NEAR(total, area, 1e-9 * area) << solver;
    // Tolerances as in PointLight.EverySolverMeetsTheInterreflectionFormulaInAPointLitRoom.
    const std::string name = solver;
    const double tolerance = name == "stochastic" || name == "gauss-seidel" || name == "progressive" ? 0.01 : 0.003;
    EXPECT_NEAR(sum / total / expected, 1.0, tolerance) << solver;
    EXPECT_NEAR(direct / (rho * flux), 1.0, 0.003) << solver;
    // The back faces the lamp: lit directly, far more than the front.
    EXPECT_GT(back, 2 * front) << solver;
    EXPECT_GT(front, 0) << solver;
  }
}

TEST(TwoSided, AOneSidedPanelLosesTheLightOnItsBack) {
  // The control for the test above: the same room with a one-sided panel is
  // short of the formula by about the share its back absorbs.
  const double rho = 0.6;
  const Scene scene = roomWithPanel(rho, false);
  ASSERT_EQ(scene.faces.size(), 7u);
  const double area = 2 * (4 * 2.5 + 4 * 3 + 3 * 2.5) + 1.8 * 1.6;
  const double expected = scene.lights[0].power()[0] / (area * (1 - rho));
  RayTracer tracer(scene);
  MeshOptions mesh;
  mesh.maxEdgeLength = 0.5;
  SolverOptions options;
  options.tolerance = 1e-5;
  Solution s = meshAndSolve(scene, tracer, mesh, options);
  double sum = 0;
  for (size_t e = 0; e < s.elementCount(); ++e) sum += s.irradiance[e][0] * s.mesh.elements[e].area;
  EXPECT_LT(sum / area / expected, 0.95);
}

std::string writeFile(const std::string &name, const std::string &text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(TwoSided, JsonMaterialsSayTwoSided) {
  const std::string base = R"({"camera": {"eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0]},
    "materials": {"paper": {"type": "lambertian", "reflectance": 0.7, "two_sided": TWO}},
    "objects": [{"name": "sheet", "type": "quad", "material": "paper",
                 "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}]})";
  auto withValue = [&](const std::string &value) {
    std::string text = base;
    text.replace(text.find("TWO"), 3, value);
    return text;
  };
  const Scene two = parseSceneJson(withValue("true"), "two.json");
  ASSERT_EQ(two.faces.size(), 2u);
  EXPECT_TRUE(two.faces[1].back);
  EXPECT_EQ(parseSceneJson(withValue("false"), "one.json").faces.size(), 1u);
  try {
    parseSceneJson(withValue("\"yes\""), "bad.json");
    FAIL() << "a string accepted";
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().jsonPath, "/materials/paper/two_sided");
    EXPECT_NE(e.message().find("true or false"), std::string::npos) << e.message();
  }
  std::string glass = withValue("true");
  glass.replace(glass.find("\"lambertian\", \"reflectance\": 0.7"), 33, "\"dielectric\"");
  EXPECT_THROW(parseSceneJson(glass, "glass.json"), InputError);
}

TEST(TwoSided, MgfSidesTwoGivesEveryFaceABack) {
  const std::string path = writeFile("radiant_two_sided.mgf", R"(m paper =
	c
		cxy 0.333 0.333
	rd 0.7
	sides 2
m lamp =
	ed 100
v a =
	p 0 0 0
v b =
	p 1 0 0
v c =
	p 1 1 0
v d =
	p 0 1 0
v e =
	p 0 0 2
v f =
	p 1 0 2
v g =
	p 1 1 2
v h =
	p 0 1 2
m paper
f a b c d
m lamp
f e h g f
)");
  const Scene scene = loadScene(path);
  size_t backs = 0;
  for (const Face &f : scene.faces) backs += f.back;
  EXPECT_EQ(backs, 1u);  // the paper's face; the lamp is one-sided
  for (const std::string &w : scene.warnings) EXPECT_EQ(w.find("sides"), std::string::npos) << w;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace radiant
