// Scene loading: the bundled scenes against the published Cornell box data
// ("Cornell Box Data", graphics.cornell.edu/online/box/data.html), every class
// of bad input (one table), the OBJ/MTL mapping and object transforms.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "input_errors.h"
#include "scene/load_scene.h"
#include "scene/overlapping_faces.h"
#include "temp_dir.h"
#include "util/error.h"

namespace radiant {
namespace {

namespace fs = std::filesystem;

std::string sourcePath(const std::string &relative) {
  return std::string(RADIANT_SOURCE_DIR) + "/" + relative;
}

int objectIndex(const Scene &scene, const std::string &name) {
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no object named " << name;
  return -1;
}

std::vector<const Face *> facesOf(const Scene &scene, const std::string &name) {
  int index = objectIndex(scene, name);
  std::vector<const Face *> faces;
  for (const Face &f : scene.faces)
    if (static_cast<int>(f.object) == index) faces.push_back(&f);
  return faces;
}

double objectArea(const Scene &scene, const std::string &name) {
  double area = 0;
  for (const Face *f : facesOf(scene, name)) area += scene.faceArea(*f);
  return area;
}

/// Σ area · normal: for a planar object its length is the area; for the
/// non-planar Cornell left wall it is the projected (Newell) area.
Vec3 objectVectorArea(const Scene &scene, const std::string &name) {
  Vec3 sum;
  for (const Face *f : facesOf(scene, name)) sum += scene.faceNormal(*f) * scene.faceArea(*f);
  return sum;
}

Vec3 faceCentroid(const Scene &scene, const Face &f) {
  Vec3 c;
  for (int k = 0; k < f.vertexCount; ++k) c += scene.positions[f.vertices[k]];
  return c / f.vertexCount;
}

bool hasWarning(const Scene &scene, const std::string &text) {
  for (const std::string &w : scene.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

// ---------------------------------------------------------------------------
// The bundled Cornell box

class SceneLoaderCornell : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(loadScene(sourcePath("scenes/cornell-box/scene.json"))); }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  static Scene *scene_;
};
Scene *SceneLoaderCornell::scene_ = nullptr;

TEST_F(SceneLoaderCornell, LoadsWithCameraAndNoWarnings) {
  const Scene &s = *scene_;
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_EQ(s.droppedDegenerateFaces, 0u);
  EXPECT_EQ(s.objects.size(), 16u);
  EXPECT_NEAR(s.camera.eye.x, 0.278, 1e-12);
  EXPECT_NEAR(s.camera.eye.y, 0.273, 1e-12);
  EXPECT_NEAR(s.camera.eye.z, -0.8, 1e-12);
  EXPECT_NEAR(s.camera.target.z, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.camera.verticalFovDegrees, 39.3077);
  EXPECT_EQ(s.render.width, 512);
  EXPECT_EQ(s.render.height, 512);
  size_t emitters = 0;
  for (const Face &f : s.faces) emitters += s.materials[f.material].isEmitter();
  EXPECT_GT(emitters, 0u);
  for (const Face *f : facesOf(s, "light")) {
    const Material &m = s.materials[f->material];
    EXPECT_DOUBLE_EQ(m.emission[0], 18.387);
    EXPECT_DOUBLE_EQ(m.diffuse[0], 0.885809);
  }
}

TEST_F(SceneLoaderCornell, PublishedAreas) {
  struct Row {
    const char *object;
    double areaM2;
  };
  // The published quads' (Newell) areas, mm² → m².
  const Row rows[] = {{"floor", 0.3082310},           {"ceiling", 0.3109152},       {"back-wall", 0.3033766},
                      {"right-wall", 0.306889},       {"left-wall", 0.306902},      {"light", 0.01365},
                      {"short-block-top", 0.0276330}, {"tall-block-top", 0.0276265}};
  for (const Row &row : rows) {
    SCOPED_TRACE(row.object);
    // The published areas are Newell (projected) areas; every surface but the
    // left wall is planar, where that is also the surface area.
    EXPECT_NEAR(length(objectVectorArea(*scene_, row.object)), row.areaM2, 1e-6 * row.areaM2);
    if (std::string(row.object) != "left-wall") {
      EXPECT_NEAR(objectArea(*scene_, row.object), row.areaM2, 1e-6 * row.areaM2);
    }
  }
  // The left wall's fourth vertex is 3.2 mm off the plane: split into two
  // triangles its true area is 306 904.5 mm², 8e-6 above the projected area.
  EXPECT_NEAR(objectArea(*scene_, "left-wall"), 0.3069045, 1e-5 * 0.3069045);
  EXPECT_EQ(facesOf(*scene_, "left-wall").size(), 2u);
  EXPECT_EQ(facesOf(*scene_, "floor").size(), 1u);
  EXPECT_EQ(facesOf(*scene_, "floor").front()->vertexCount, 4);
}

TEST_F(SceneLoaderCornell, WallsFaceIntoTheRoom) {
  struct Row {
    const char *object;
    Vec3 normal;
    double tolerance;
  };
  const Row rows[] = {{"floor", {0, 1, 0}, 1e-12},      {"ceiling", {0, -1, 0}, 1e-12},
                      {"light", {0, -1, 0}, 1e-12},     {"back-wall", {0, 0, -1}, 1e-12},
                      {"right-wall", {1, 0, 0}, 1e-12}, {"left-wall", {-1, 0, 0}, 0.02}};
  for (const Row &row : rows) {
    SCOPED_TRACE(row.object);
    for (const Face *f : facesOf(*scene_, row.object)) {
      Vec3 n = scene_->faceNormal(*f);
      EXPECT_NEAR(n.x, row.normal.x, row.tolerance);
      EXPECT_NEAR(n.y, row.normal.y, row.tolerance);
      EXPECT_NEAR(n.z, row.normal.z, row.tolerance);
    }
  }
}

TEST_F(SceneLoaderCornell, BlockFacesPointOutward) {
  for (const char *block : {"short-block", "tall-block"}) {
    std::vector<std::string> names;
    for (const char *side : {"top", "left", "right", "front", "back"}) names.push_back(std::string(block) + "-" + side);
    Vec3 centre;
    int count = 0;
    for (const std::string &name : names)
      for (const Face *f : facesOf(*scene_, name)) {
        centre += faceCentroid(*scene_, *f);
        ++count;
      }
    centre = centre / count;
    centre.y = 0;  // the blocks have no bottom; the centre of their footprint lies below every face centroid
    for (const std::string &name : names)
      for (const Face *f : facesOf(*scene_, name)) {
        Vec3 fromCentre = faceCentroid(*scene_, *f) - centre;
        fromCentre.y = name.ends_with("top") ? 1 : 0;
        EXPECT_GT(dot(scene_->faceNormal(*f), fromCentre), 0) << name;
      }
  }
}

TEST_F(SceneLoaderCornell, LightIsJustBelowTheCeiling) {
  for (const Face *f : facesOf(*scene_, "light"))
    for (int k = 0; k < f->vertexCount; ++k) EXPECT_NEAR(scene_->positions[f->vertices[k]].y, 0.5487, 1e-12);
}

// ---------------------------------------------------------------------------
// Other bundled scenes

/// A valid 1 × 1 8-bit grey PNG (value 128): textures are loaded with the scene.
const std::string kTinyPng(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x01\x00\x00\x00\x01\x08\x00\x00\x00"
    "\x00\x3a\x7e\x9b\x55\x00\x00\x00\x0a\x49\x44\x41\x54\x78\x9c\x63\x68\x00\x00\x00\x82\x00\x81\x77\xcd\x72\xb6\x00"
    "\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82",
    67);

TEST(SceneLoaderScenes, FurnaceWallsAllFaceInward) {
  Scene s = loadScene(sourcePath("scenes/furnace/scene.json"));
  EXPECT_TRUE(s.warnings.empty());
  ASSERT_EQ(s.faces.size(), 6u);
  Vec3 lo = s.positions.front(), hi = lo;
  for (const Vec3 &p : s.positions)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  Vec3 centre = (lo + hi) * 0.5;
  double total = 0;
  for (const Face &f : s.faces) {
    EXPECT_GT(dot(s.faceNormal(f), centre - faceCentroid(s, f)), 0) << s.objects[f.object].name;
    const Material &m = s.materials[f.material];
    EXPECT_DOUBLE_EQ(m.emission.min(), 1.0);
    EXPECT_DOUBLE_EQ(m.diffuse.max(), 0.5);
    total += s.faceArea(f);
  }
  EXPECT_NEAR(total, 6.0, 1e-12);
  // The camera is inside the box: allowed.
  for (int a = 0; a < 3; ++a) EXPECT_TRUE(s.camera.eye[a] > lo[a] && s.camera.eye[a] < hi[a]);
}

TEST(SceneLoaderScenes, CornellSpecularHasMirrorAndGlassSpheres) {
  Scene s = loadScene(sourcePath("scenes/cornell-specular/scene.json"));
  EXPECT_TRUE(s.warnings.empty());
  for (const char *name : {"mirror-sphere", "glass-sphere"}) {
    SCOPED_TRACE(name);
    std::vector<const Face *> faces = facesOf(s, name);
    ASSERT_FALSE(faces.empty());
    Vec3 centre;
    double minY = 1e9;
    size_t vertices = 0;
    for (const Face *f : faces)
      for (int k = 0; k < f->vertexCount; ++k) {
        centre += s.positions[f->vertices[k]];
        minY = std::min(minY, s.positions[f->vertices[k]].y);
        ++vertices;
      }
    centre = centre / static_cast<double>(vertices);
    EXPECT_NEAR(minY, 0.0, 1e-9);  // resting on the floor
    for (const Face *f : faces) EXPECT_GT(dot(s.faceNormal(*f), faceCentroid(s, *f) - centre), 0);
  }
  EXPECT_EQ(s.materials[facesOf(s, "mirror-sphere").front()->material].kind, MaterialKind::Mirror);
  const Material &glass = s.materials[facesOf(s, "glass-sphere").front()->material];
  EXPECT_EQ(glass.kind, MaterialKind::Dielectric);
  EXPECT_DOUBLE_EQ(glass.ior, 1.5);
}

// ---------------------------------------------------------------------------
// Bad input: one row per rule. Each row patches a small valid scene.

/// A valid scene; `materials`, `objects` and `extra` (top-level keys) are spliced in.
std::string sceneText(const std::string &materials, const std::string &objects, const std::string &extra = "") {
  return R"({
  "units": "metres",
  "camera": {"eye": [0.5, 0.5, 3], "target": [0.5, 0.5, 0], "up": [0, 1, 0], "fov": 40},
  "image": {"width": 64, "height": 64},)" +
         extra + R"(
  "materials": {)" +
         materials + R"(},
  "objects": [)" +
         objects + R"(]
})";
}

const std::string kLamp = R"("lamp": {"reflectance": 0.5, "emission": 1})";
const std::string kQuad =
    R"({"name": "q", "type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "lamp"})";

struct BadInput {
  const char *name;
  std::string text;
  std::string expectedMessage;  ///< substring of what()
  std::string expectedPath;     ///< JSON path, or "" to skip
  bool expectLine = false;      ///< a line and column for syntax errors
};

std::string quadWithMaterial(const std::string &material) {
  return sceneText(R"("m": )" + material + "," + kLamp,
                   kQuad + R"(, {"type": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "material": "m"})");
}

std::vector<BadInput> badInputs() {
  const std::string valid = sceneText(kLamp, kQuad);
  std::vector<BadInput> rows = {
      {"malformed JSON", "{\n  \"objects\": [\n  }\n}", "invalid JSON", "", true},
      {"truncated JSON", valid.substr(0, valid.size() / 2), "invalid JSON", "", true},
      {"number too large (inf)", sceneText(R"("lamp": {"reflectance": 0.5, "emission": 1e999})", kQuad), "too large",
       "", true},
      {"unknown material key", quadWithMaterial(R"({"reflectence": 0.5})"),
       "unknown key 'reflectence'; did you mean 'reflectance'?", "/materials/m/reflectence"},
      {"unknown top-level key", sceneText(kLamp, kQuad, R"( "camra": {},)"), "did you mean 'camera'?", "/camra"},
      {"unknown object key", sceneText(kLamp, R"({"type": "quad", "vertice": [], "material": "lamp"})"),
       "did you mean 'vertices'?", "/objects/0/vertice"},
      {"unknown camera key", sceneText(kLamp, kQuad, R"( "render": {"sp": 4},)"), "did you mean 'spp'?", "/render/sp"},
      {"key of another material type", quadWithMaterial(R"({"roughness": 0.3})"),
       "does not apply to a lambertian material", "/materials/m/roughness"},
      {"unknown object type", sceneText(kLamp, R"({"type": "quadd"})"), "did you mean 'quad'?", "/objects/0/type"},
      {"unknown material type", quadWithMaterial(R"({"type": "miror"})"), "did you mean 'mirror'?",
       "/materials/m/type"},
      {"unknown units", sceneText(kLamp, kQuad, R"( "units": "milimetres",)"), "did you mean 'millimetres'?", "/units"},
      {"unsupported version", sceneText(kLamp, kQuad, R"( "version": 2,)"), "version", "/version"},
      {"undefined material on a quad",
       sceneText(kLamp, R"({"type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "lamb"})"),
       "did you mean 'lamp'?", "/objects/0/material"},
      {"wrong value type", quadWithMaterial(R"({"reflectance": "red"})"),
       "expected an array of 3 numbers or a number, got a string", "/materials/m/reflectance"},
      {"wrong vertex count", sceneText(kLamp, R"({"type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0]]})"),
       "expected an array of 4 elements", "/objects/0/vertices"},
      {"missing OBJ file", sceneText(kLamp, kQuad + R"(, {"type": "obj", "file": "no-such-model.obj"})"),
       "no-such-model.obj", "/objects/1/file"},
      {"missing texture file", quadWithMaterial(R"({"texture": "no-such-texture.png"})"), "no-such-texture.png",
       "/materials/m/texture"},
      {"negative reflectance", quadWithMaterial(R"({"reflectance": [0.5, -0.1, 0.5]})"), "negative",
       "/materials/m/reflectance"},
      {"negative emission", quadWithMaterial(R"({"emission": -1})"), "negative", "/materials/m/emission"},
      {"reflectance 1 diverges", quadWithMaterial(R"({"reflectance": [0.5, 1.0, 0.5]})"), "diverge",
       "/materials/m/reflectance"},
      {"mirror reflectance above 1", quadWithMaterial(R"({"type": "mirror", "reflectance": 1.01})"), "≤ 1",
       "/materials/m/reflectance"},
      {"glossy diffuse + specular above 1",
       quadWithMaterial(R"({"type": "glossy", "reflectance": 0.6, "specular": 0.5})"), "exceeds 1", "/materials/m"},
      {"glossy roughness 0", quadWithMaterial(R"({"type": "glossy", "roughness": 0})"), "(0, 1]",
       "/materials/m/roughness"},
      {"dielectric ior 0", quadWithMaterial(R"({"type": "dielectric", "ior": 0})"), "index of refraction",
       "/materials/m/ior"},
      {"negative radius", sceneText(kLamp, kQuad + R"(, {"type": "sphere", "center": [0,0,0], "radius": -1})"),
       "must be > 0", "/objects/1/radius"},
      {"negative fov", sceneText(kLamp, kQuad, R"( "camera": {"eye": [0,0,3], "target": [0,0,0], "fov": -10},)"), "fov",
       "/camera/fov"},
      {"fov 180", sceneText(kLamp, kQuad, R"( "camera": {"eye": [0,0,3], "target": [0,0,0], "fov": 180},)"), "fov",
       "/camera/fov"},
      {"eye equals target", sceneText(kLamp, kQuad, R"( "camera": {"eye": [1,2,3], "target": [1,2,3]},)"),
       "target equals eye", "/camera/target"},
      {"up parallel to view",
       sceneText(kLamp, kQuad, R"( "camera": {"eye": [0,0,3], "target": [0,0,0], "up": [0,0,2]},)"), "parallel",
       "/camera/up"},
      {"image width 0", sceneText(kLamp, kQuad, R"( "image": {"width": 0, "height": 64},)"), "[1, 16384]",
       "/image/width"},
      {"image height too large", sceneText(kLamp, kQuad, R"( "image": {"width": 64, "height": 100000},)"), "[1, 16384]",
       "/image/height"},
      {"image too many pixels", sceneText(kLamp, kQuad, R"( "image": {"width": 16384, "height": 16384},)"), "2^26",
       "/image/height"},
      {"image width not an integer", sceneText(kLamp, kQuad, R"( "image": {"width": 64.5},)"), "integer",
       "/image/width"},
      {"spp 0", sceneText(kLamp, kQuad, R"( "render": {"spp": 0},)"), "[1, 1048576]", "/render/spp"},
      {"spp too large", sceneText(kLamp, kQuad, R"( "render": {"spp": 1e12},)"), "[1, 1048576]", "/render/spp"},
      {"negative time", sceneText(kLamp, kQuad, R"( "render": {"time": -1},)"), "time", "/render/time"},
      {"zero scale",
       sceneText(
           kLamp,
           R"({"type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "transform": {"scale": [1, 0, 1]}})"),
       "scale", "/objects/0/transform/scale"},
      {"duplicate object name", sceneText(kLamp, kQuad + "," + kQuad), "already used", "/objects/1"},
  };
  return rows;
}

TEST(SceneLoaderErrors, EveryBadInputIsAnInputErrorWithItsLocation) {
  test::TempDir dir("scene-loader");
  const std::string path = dir.file("scene.json");
  for (const BadInput &row : badInputs()) {
    SCOPED_TRACE(row.name);
    try {
      Scene scene = parseSceneJson(row.text, path);
      ADD_FAILURE() << "no error for: " << row.text;
    } catch (const InputError &e) {
      std::string what = e.what();
      EXPECT_NE(what.find(row.expectedMessage), std::string::npos) << what;
      EXPECT_EQ(e.location().file, path);
      if (!row.expectedPath.empty()) {
        EXPECT_EQ(e.location().jsonPath, row.expectedPath) << what;
      }
      if (row.expectLine) {
        EXPECT_GT(e.location().line, 0) << what;
        EXPECT_GT(e.location().column, 0) << what;
      }
    }
  }
}

TEST(SceneLoaderErrors, SyntaxErrorLineAndColumn) {
  try {
    parseSceneJson("{\n  \"objects\": [1,\n    2 3]\n}", "x.json");
    FAIL();
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().line, 3);
    EXPECT_EQ(e.location().column, 7);
  }
}

TEST(SceneLoaderErrors, MissingSceneFile) {
  EXPECT_THROW(loadScene("/nonexistent/radiant/scene.json"), InputError);
}

TEST(SceneLoaderWarnings, DegenerateFacesAreDroppedAndCounted) {
  Scene s = parseSceneJson(sceneText(kLamp, kQuad + R"(,
        {"name": "line", "type": "triangle", "vertices": [[0,0,0],[1,0,0],[2,0,0]]},
        {"name": "point", "type": "triangle", "vertices": [[0,0,0],[0,0,0],[0,0,0]]},
        {"name": "flat", "type": "quad", "vertices": [[0,0,0],[1,0,0],[2,0,0],[3,0,0]]})"),
                           "s.json");
  EXPECT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(s.droppedDegenerateFaces, 3u);
  EXPECT_TRUE(hasWarning(s, "dropped 3 degenerate faces"));
  // Each by its object and the centroid of its corners (scene/load_changes.h), the first in the warning.
  EXPECT_TRUE(hasWarning(s, "the first in 'line' at (1, 0, 0) m: zero area"));
  ASSERT_EQ(s.loadChanges.count(LoadChangeKind::DegenerateFace), 3u);
  const char *names[] = {"line", "point", "flat"};
  const Vec3 centroids[] = {{1, 0, 0}, {0, 0, 0}, {1.5, 0, 0}};
  for (size_t i = 0; i < 3; ++i) {
    const LoadChange &c = s.loadChanges.listed[i];
    EXPECT_EQ(c.kind, LoadChangeKind::DegenerateFace);
    EXPECT_EQ(s.objects[c.object].name, names[i]);
    EXPECT_NEAR(length(c.position - centroids[i]), 0.0, 1e-12) << names[i];
  }
}

TEST(SceneLoaderWarnings, NoEmitterIsAWarningNotAnError) {
  Scene s = parseSceneJson(
      sceneText(R"("grey": {"reflectance": 0.5})",
                R"({"type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "grey"})"),
      "s.json");
  EXPECT_TRUE(hasWarning(s, "no emitter and no light: the image will be black"));
}

TEST(SceneLoaderWarnings, AllowedEdgeValues) {
  // Mirror reflectance 1 and glossy diffuse + specular = 1 are allowed; a camera inside geometry too.
  Scene s = parseSceneJson(
      sceneText(kLamp + R"(, "mirror": {"type": "mirror", "reflectance": 1},
                 "shiny": {"type": "glossy", "reflectance": 0.5, "specular": 0.5, "roughness": 1})",
                kQuad + R"(, {"type": "sphere", "center": [0.5, 0.5, 3], "radius": 1, "material": "mirror"})"),
      "s.json");
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneLoaderWarnings, DefaultsAndComments) {
  Scene s = parseSceneJson(R"({"comment": "c", "objects": [{"comment": "c", "type": "quad",
      "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})",
                           "s.json");
  ASSERT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(s.materials[s.faces[0].material].name, "default");
  EXPECT_DOUBLE_EQ(s.materials[s.faces[0].material].diffuse[1], 0.5);
  EXPECT_EQ(s.render.width, 512);
  EXPECT_EQ(s.render.samplesPerPixel, 64);
  // Without a camera the scene is framed from +z.
  EXPECT_GT(s.camera.eye.z, 1.0);
  EXPECT_NEAR(s.camera.target.x, 0.5, 1e-12);
}

// ---------------------------------------------------------------------------
// OBJ / MTL

const char *kMtl = R"(# test materials
newmtl matte
Kd 0.2 0.4 0.6

newmtl lamp
Kd 0.1 0.1 0.1
Ke 5 4 3

newmtl chrome
illum 3
Kd 0.5 0.5 0.5
Ks 0.9 0.8 0.7

newmtl glass
illum 7
Ni 1.33
Tf 0.9 0.95 1

newmtl plastic
illum 2
Kd 0.3 0.3 0.3
Ks 0.25 0.25 0.25
Ns 98

newmtl overridden
Kd 0.1 0.1 0.1
)";

const char *kObj = R"(mtllib test.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0.5 1.5 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 0 2
v 1 0 2
v 1 1 2
v 0 0 3
v 1 0 3
v 1 1 3
v 0 0 4
v 1 0 4
v 1 1 4
v 0 0 5
v 1 0 5
v 1 1 5
v 0 0 6
v 1 0 6
v 1 1 6
v 0 0 7
v 1 0 7
v 1 1 7
vn 0 0 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
o parts
usemtl matte
f 1/1/1 2/2/1 3/3/1 4/4/1
usemtl lamp
f 6 7 8
usemtl chrome
f 9 10 11
usemtl glass
f 12 13 14
usemtl plastic
f 15 16 17
o more
usemtl overridden
f 18 19 20
usemtl jsononly
f 21 22 23
usemtl nowhere
f 24 25 26
f 1 2 3 5 4
)";

TEST(SceneLoaderObj, MtlMappingAndJsonOverride) {
  test::TempDir dir("scene-loader");
  dir.write("test.mtl", kMtl);
  dir.write("model.obj", kObj);
  std::string path = dir.write(
      "scene.json",
      sceneText(
          R"("overridden": {"reflectance": 0.7, "emission": 2}, "jsononly": {"type": "mirror", "reflectance": 0.5})",
          R"({"name": "model", "type": "obj", "file": "model.obj"})"));
  Scene s = loadScene(path);
  auto materialOf = [&](size_t face) -> const Material & { return s.materials[s.faces[face].material]; };
  // 8 faces with 3–4 vertices, then a pentagon fan-split into 3 triangles.
  ASSERT_EQ(s.faces.size(), 11u);
  EXPECT_EQ(s.faces[0].vertexCount, 4);
  EXPECT_EQ(s.faces[0].uvs[2], 2);
  EXPECT_GE(s.faces[0].normals[0], 0);

  EXPECT_EQ(materialOf(0).kind, MaterialKind::Lambertian);
  EXPECT_DOUBLE_EQ(materialOf(0).diffuse[2], 0.6);
  EXPECT_DOUBLE_EQ(materialOf(1).emission[0], 5.0);
  EXPECT_TRUE(materialOf(1).isEmitter());
  EXPECT_EQ(materialOf(2).kind, MaterialKind::Mirror);
  EXPECT_NEAR(materialOf(2).specular[1], 0.8, 1e-6);
  EXPECT_EQ(materialOf(3).kind, MaterialKind::Dielectric);
  EXPECT_NEAR(materialOf(3).ior, 1.33, 1e-6);
  EXPECT_NEAR(materialOf(3).specular[0], 0.9, 1e-6);
  EXPECT_EQ(materialOf(4).kind, MaterialKind::Glossy);
  EXPECT_NEAR(materialOf(4).roughness, std::sqrt(2.0 / 100.0), 1e-6);
  EXPECT_NEAR(materialOf(4).specular[0], 0.25, 1e-6);
  // usemtl names defined in the JSON win over the MTL, and may exist only there.
  EXPECT_DOUBLE_EQ(materialOf(5).diffuse[0], 0.7);
  EXPECT_EQ(materialOf(6).kind, MaterialKind::Mirror);
  // An unknown name gets the default material, with a warning.
  EXPECT_EQ(materialOf(7).name, "default");
  EXPECT_TRUE(hasWarning(s, "nowhere"));

  EXPECT_EQ(s.objects[s.faces[0].object].name, "model/parts");
  EXPECT_EQ(s.objects[s.faces[5].object].name, "model/more");
}

TEST(SceneLoaderObj, DefaultMaterialFromJsonOrMtl) {
  test::TempDir dir("scene-loader");
  dir.write("test.mtl", kMtl);
  dir.write("plain.obj", "mtllib test.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Scene fromMtl =
      loadScene(dir.write("a.json", sceneText(kLamp, R"({"type": "obj", "file": "plain.obj", "material": "lamp"})")));
  // "lamp" is in both: the JSON one (reflectance 0.5, emission 1) wins.
  EXPECT_DOUBLE_EQ(fromMtl.materials[fromMtl.faces[0].material].emission[0], 1.0);
  Scene onlyMtl =
      loadScene(dir.write("b.json", sceneText(kLamp, R"({"type": "obj", "file": "plain.obj", "material": "chrome"})")));
  EXPECT_EQ(onlyMtl.materials[onlyMtl.faces[0].material].kind, MaterialKind::Mirror);
  try {
    loadScene(dir.write("c.json", sceneText(kLamp, R"({"type": "obj", "file": "plain.obj", "material": "chrom"})")));
    FAIL();
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().jsonPath, "/objects/0/material");
    EXPECT_NE(std::string(e.what()).find("did you mean 'chrome'?"), std::string::npos) << e.what();
  }
}

TEST(SceneLoaderObj, BadLinesNameTheFileAndLine) {
  struct Row {
    const char *name;
    std::string obj;
    int line;
    const char *message;
  };
  const Row rows[] = {
      {"face index out of range", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 99\n", 5, "out of range"},
      {"non-numeric coordinate", "v 0 0 0\nv 1 x 2\n", 2, "'x'"},
      {"too few coordinates", "v 0 0\n", 1, "at least 3"},
      {"zero index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "vertex reference"},
      {"negative index out of range", "v 0 0 0\nf -1 -2 -3\n", 2, "out of range"},
      {"face with two vertices", "v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "at least 3"},
      {"normal index out of range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", 4, "normal index"},
      {"missing mtllib", "mtllib nothing.mtl\n", 1, "nothing.mtl"},
  };
  test::TempDir dir("scene-loader");
  for (const Row &row : rows) {
    SCOPED_TRACE(row.name);
    std::string obj = dir.write("bad.obj", row.obj);
    try {
      loadScene(obj);
      ADD_FAILURE() << "no error";
    } catch (const InputError &e) {
      EXPECT_EQ(e.location().file, obj);
      EXPECT_EQ(e.location().line, row.line) << e.what();
      EXPECT_NE(std::string(e.what()).find(row.message), std::string::npos) << e.what();
    }
  }
}

TEST(SceneLoaderObj, MissingTextureNamesTheMtlLine) {
  test::TempDir dir("scene-loader");
  dir.write("t.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Kd textures/missing.png\n");
  std::string obj = dir.write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  try {
    loadScene(obj);
    FAIL();
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().file, dir.file("t.mtl"));
    EXPECT_EQ(e.location().line, 3);
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos) << e.what();
  }
  // With the file present the path is resolved against the MTL's folder.
  fs::create_directories(dir.file("textures"));
  dir.write("textures/missing.png", kTinyPng);
  dir.write("t.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Kd textures/missing.png\nbump -bm 0.25 textures/missing.png\n");
  Scene s = loadScene(obj);
  const Material &m = s.materials[s.faces[0].material];
  EXPECT_EQ(fs::path(m.diffuseTexture), fs::path(dir.file("textures/missing.png")));
  EXPECT_EQ(m.bumpTexture, m.diffuseTexture);
  EXPECT_NEAR(m.bumpScale, 0.25, 1e-6);
}

TEST(SceneLoaderObj, TexturePathsWithWindowsSeparatorsAreFound) {
  // MTL files written on Windows (assimp's spider: `map_Kd .\SpiderTex.jpg`).
  test::TempDir dir("scene-loader");
  fs::create_directories(dir.file("textures"));
  dir.write("textures/wood.png", kTinyPng);
  dir.write("t.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Kd .\\textures\\wood.png\n");
  std::string obj = dir.write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  Scene s = loadScene(obj);
  EXPECT_EQ(fs::path(s.materials[s.faces[0].material].diffuseTexture), fs::path(dir.file("textures/wood.png")));
}

TEST(SceneLoaderObj, BareObjGetsAFramingCameraAndWarnings) {
  test::TempDir dir("scene-loader");
  std::string obj = dir.write("box.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 9 9 9\nf 1 2 3 4\n");
  Scene s = loadScene(obj);
  ASSERT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(s.objects[0].name, "box");
  EXPECT_TRUE(hasWarning(s, "no emitter"));
  EXPECT_DOUBLE_EQ(s.camera.verticalFovDegrees, 40.0);
  EXPECT_GT(s.camera.eye.z, s.camera.target.z);
  EXPECT_EQ(s.render.width, 512);
}

TEST(SceneLoaderObj, KdOfOneIsScaledWithAWarning) {
  // Exporters write Kd 1 1 1 ("white") and Kd + Ks > 1 (3ds Max: Kd 0.2, Ks
  // 0.9): loaded, scaled by one factor to conserve energy, said once.
  test::TempDir dir("scene-loader");
  dir.write("w.mtl", "newmtl white\nKd 1 0.5 0.5\nnewmtl max\nillum 2\nKd 0.2 0.2 0.2\nKs 0.9 0.9 0.9\nNs 50\n");
  std::string obj = dir.write(
      "w.obj", "mtllib w.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl white\nf 1 2 3\nusemtl max\nf 1 2 4\n");
  Scene s = loadScene(obj);
  const Material &white = s.materials[s.faces[0].material];
  EXPECT_DOUBLE_EQ(white.diffuse[0], kMaxDiffuseReflectance);
  EXPECT_DOUBLE_EQ(white.diffuse[1], 0.5 * kMaxDiffuseReflectance);  // the colour kept
  const Material &max = s.materials[s.faces[1].material];
  EXPECT_NEAR(max.diffuse[0] + max.specular[0], 1.0, 1e-12);
  EXPECT_NEAR(max.specular[0] / max.diffuse[0], 4.5, 1e-9);  // the ratio kept
  EXPECT_TRUE(hasWarning(s, "w.mtl:1: material 'white'"));
  EXPECT_TRUE(hasWarning(s, "w.mtl:3: material 'max': Kd + Ks = 1.1"));
}

// ---------------------------------------------------------------------------
// Transforms and units

TEST(SceneLoaderTransform, ScaleTwoQuadruplesArea) {
  const std::string quad = R"("type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "lamp")";
  Scene s = parseSceneJson(
      sceneText(
          kLamp,
          "{\"name\": \"a\", " + quad + "}, {\"name\": \"b\", " + quad +
              R"(, "transform": {"scale": 2, "rotate": [{"axis": [0,1,0], "degrees": 90}], "translate": [5,0,0]}})"),
      "s.json");
  EXPECT_NEAR(objectArea(s, "b"), 4 * objectArea(s, "a"), 1e-12);
  // Rotating +z by 90° about +y gives +x; translate is applied last.
  const Face &b = *facesOf(s, "b").front();
  Vec3 n = s.faceNormal(b);
  EXPECT_NEAR(n.x, 1.0, 1e-12);
  EXPECT_NEAR(s.positions[b.vertices[1]].z, -2.0, 1e-12);
  EXPECT_NEAR(s.positions[b.vertices[1]].x, 5.0, 1e-12);
}

TEST(SceneLoaderTransform, UnitsScaleGeometryAndCamera) {
  Scene s = parseSceneJson(R"({"units": "cm",
      "camera": {"eye": [0, 0, 300], "target": [0, 0, 0]},
      "objects": [{"name": "a", "type": "quad", "vertices": [[0,0,0],[100,0,0],[100,100,0],[0,100,0]]},
                  {"name": "b", "type": "quad", "vertices": [[0,0,0],[100,0,0],[100,100,0],[0,100,0]],
                   "transform": {"translate": [100, 0, 0]}}]})",
                           "s.json");
  EXPECT_NEAR(objectArea(s, "a"), 1.0, 1e-12);
  EXPECT_NEAR(s.camera.eye.z, 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.metresPerUnit, 0.01);
  EXPECT_NEAR(s.positions[facesOf(s, "b").front()->vertices[0]].x, 1.0, 1e-12);
}

TEST(SceneLoaderTransform, SphereStaysOutwardUnderMirroringScale) {
  for (const char *transform : {R"({})", R"({"scale": [-1, 1, 1]})", R"({"scale": [2, -0.5, 1]})"}) {
    SCOPED_TRACE(transform);
    Scene s = parseSceneJson(
        sceneText(kLamp, kQuad + R"(, {"name": "ball", "type": "sphere", "center": [0, 3, 0], "radius": 1,
                  "segments": 32, "transform": )" +
                             std::string(transform) + "}"),
        "s.json");
    std::vector<const Face *> faces = facesOf(s, "ball");
    ASSERT_FALSE(faces.empty());
    Vec3 centre;
    for (const Face *f : faces) centre += faceCentroid(s, *f);
    centre = centre / static_cast<double>(faces.size());
    for (const Face *f : faces) {
      Vec3 outward = faceCentroid(s, *f) - centre;
      EXPECT_GT(dot(s.faceNormal(*f), outward), 0);
      for (int k = 0; k < f->vertexCount; ++k) {
        ASSERT_GE(f->normals[k], 0);
        EXPECT_GT(dot(s.normals[f->normals[k]], s.positions[f->vertices[k]] - centre), 0);
      }
    }
  }
}

TEST(SceneLoaderTransform, SphereAreaApproachesFourPiRSquared) {
  Scene s = parseSceneJson(
      sceneText(kLamp,
                kQuad + R"(, {"name": "ball", "type": "sphere", "center": [0, 0, 5], "radius": 0.5, "segments": 96})"),
      "s.json");
  double expected = 4 * kPi * 0.25;
  EXPECT_NEAR(objectArea(s, "ball"), expected, 0.002 * expected);
}

TEST(SceneLoaderTransform, MirroredObjFlipsWinding) {
  test::TempDir dir("scene-loader");
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Scene s = loadScene(dir.write("s.json", sceneText(kLamp, kQuad + R"(,
      {"name": "plain", "type": "obj", "file": "tri.obj"},
      {"name": "mirrored", "type": "obj", "file": "tri.obj", "transform": {"scale": [1, 1, -1]}},
      {"name": "flipped", "type": "obj", "file": "tri.obj", "transform": {"scale": [-1, 1, 1]}})")));
  EXPECT_NEAR(s.faceNormal(*facesOf(s, "plain").front()).z, 1.0, 1e-12);
  // Mirroring z turns the +z normal into −z; mirroring x leaves it +z. Either
  // way the front stays the front of the mirrored surface.
  EXPECT_NEAR(s.faceNormal(*facesOf(s, "mirrored").front()).z, -1.0, 1e-12);
  EXPECT_NEAR(s.faceNormal(*facesOf(s, "flipped").front()).z, 1.0, 1e-12);
}

TEST(SceneLoaderQuads, NonConvexQuadIsSplitInsideItsOutline) {
  // A dart: the reflex corner is v3; a fan from v0 would cover area outside.
  Scene s = parseSceneJson(sceneText(kLamp, kQuad + R"(,
      {"name": "dart", "type": "quad", "vertices": [[0,0,0],[2,0,0],[1,2,0],[1,0.5,0]]})"),
                           "s.json");
  std::vector<const Face *> faces = facesOf(s, "dart");
  ASSERT_EQ(faces.size(), 2u);
  double area = 0;
  for (const Face *f : faces) {
    area += s.faceArea(*f);
    EXPECT_GT(s.faceNormal(*f).z, 0);
  }
  EXPECT_NEAR(area, 1.25, 1e-12);  // shoelace area of the outline
}

TEST(SceneLoaderDocs, TheDocumentedExampleLoads) {
  // docs/scene-format.md opens with a complete example; it must stay valid.
  std::ifstream in(sourcePath("docs/scene-format.md"));
  std::stringstream text;
  text << in.rdbuf();
  std::string doc = text.str();
  size_t begin = doc.find("```json\n");
  ASSERT_NE(begin, std::string::npos);
  begin += 8;
  size_t end = doc.find("```", begin);
  test::TempDir dir("scene-loader");
  fs::create_directories(dir.file("textures"));
  fs::create_directories(dir.file("models"));
  dir.write("textures/oak.png", kTinyPng);
  dir.write("textures/oak-bump.png", kTinyPng);
  dir.write("models/teapot.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  Scene s = loadScene(dir.write("scene.json", doc.substr(begin, end - begin)));
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.render.width, 800);
  EXPECT_NEAR(s.camera.eye.z, 4.0, 1e-12);
  EXPECT_EQ(s.materials[facesOf(s, "teapot").front()->material].kind, MaterialKind::Mirror);
  EXPECT_LT(s.faceNormal(*facesOf(s, "lamp").front()).y, -0.999);
}

}  // namespace
}  // namespace radiant

// ---------------------------------------------------------------------------
// Malformed and unusual input (issue 17): each once crashed, hung or was refused.

namespace radiant {
namespace {

TEST(SceneLoaderMalformed, DeeplyNestedJsonIsRefusedWithItsPosition) {
  test::TempDir dir("scene-loader");
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  for (const char *name : {"deep.json", "deep.txt"}) {
    const std::string error = test::loadErrorOf(dir.write(name, deep));
    EXPECT_NE(error.find(std::string(name) + ":1:65: arrays and objects nest more than 64"), std::string::npos)
        << error;
  }
}

TEST(SceneLoaderMalformed, HexadecimalFloatsAndHugeIndicesAreRefusedAtTheirLine) {
  test::TempDir dir("scene-loader");
  std::string error = test::loadErrorOf(dir.write("hex.obj", "v 0 0 0\nv 0x1p-2 0 0\nv 1 1 0\nf 1 2 3\n"));
  EXPECT_NE(error.find("hex.obj:2: 'v' expects finite decimal numbers, got '0x1p-2'"), std::string::npos) << error;
  error = test::loadErrorOf(dir.write("big.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 -99999999999999999999\n"));
  EXPECT_NE(error.find("big.obj:4:"), std::string::npos) << error;
}

TEST(SceneLoaderMalformed, AFaceOfAMillionVerticesIsRefused) {
  test::TempDir dir("scene-loader");
  std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf";
  for (int k = 0; k < 1000000; ++k) text += k % 2 ? " 2" : " 3";
  const std::string error = test::loadErrorOf(dir.write("ngon.obj", text + "\n"));
  EXPECT_NE(error.find("ngon.obj:4: a face of 1000000 vertices"), std::string::npos) << error.substr(0, 200);
}

TEST(SceneLoaderMalformed, RepeatedCornersLeaveAProperPolygon) {
  test::TempDir dir("scene-loader");
  // f 1 2 2 3 once reached the quad mesher with a zero-length edge and crashed the solve.
  Scene s = loadScene(dir.write("rep.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 2 3\nf 4 4 1 3 4\n"));
  ASSERT_EQ(s.faces.size(), 2u);
  EXPECT_EQ(s.faces[0].vertexCount, 3);
  EXPECT_EQ(s.faces[1].vertexCount, 3);
}

TEST(SceneLoaderMalformed, ExactRepeatsAreDroppedAndOverlapsNamed) {
  test::TempDir dir("scene-loader");
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  Scene repeated = loadScene(dir.write("dup.obj", quad + "f 1 2 3 4\nf 2 3 4 1\nf 4 3 2 1\n"));
  EXPECT_EQ(repeated.faces.size(), 2u);  // the rotated copy goes; the reversed one is the other side
  EXPECT_TRUE(hasWarning(repeated, "dropped 1 face that repeat"));
  Scene overlapping = loadScene(dir.write("overlap.obj", quad + "f 1 2 3 4\nf 1 2 3\n"));
  EXPECT_EQ(overlapping.faces.size(), 2u);
  EXPECT_TRUE(hasWarning(overlapping, "1 pair of faces overlap in one plane")) << overlapping.warnings.size();
  // Each face placed by its centroid, not only by its number (issue 38).
  EXPECT_TRUE(hasWarning(overlapping,
                         "face 0 of object 'overlap' at (0.5, 0.5, 0) m and face 1 of 'overlap' at "
                         "(0.6667, 0.3333, 0) m"))
      << (overlapping.warnings.empty() ? "" : overlapping.warnings.back());
  overlapping.metresPerUnit = 0.001;  // a millimetre scene: scene units first, metres beside them
  EXPECT_NE(describeOverlappingFaces(overlapping, findOverlappingFaces(overlapping))
                .find("at (500, 500, 0) in scene units, (0.5, 0.5, 0) m"),
            std::string::npos);
  // A tessellated floor only touches along edges.
  Scene floor = loadScene(dir.write("floor.obj", quad + "f 1 2 3\nf 1 3 4\n"));
  EXPECT_FALSE(hasWarning(floor, "overlap"));
}

TEST(SceneLoaderMalformed, OtherFormatsAreNamed) {
  test::TempDir dir("scene-loader");
  EXPECT_NE(test::loadErrorOf(dir.write("m.dae", "<?xml version=\"1.0\"?><COLLADA/>")).find("this is a COLLADA file"),
            std::string::npos);
  EXPECT_NE(test::loadErrorOf(dir.write("m.dat", "ply\nformat ascii 1.0\n")).find("this is a PLY file"),
            std::string::npos);
  EXPECT_NE(test::loadErrorOf(dir.write("m.off", "OFF\n3 1 0\n")).find("OFF"), std::string::npos);
  // MGF is read now (tests/mgf_import_test.cpp): an undefined colour is an error at its line.
  EXPECT_NE(test::loadErrorOf(dir.write("m.mgf", "c red\n")).find("m.mgf:1: colour 'red' is not defined"),
            std::string::npos);
  EXPECT_NE(test::loadErrorOf(dir.write("x.rad", "RADIANT-SOLUTION....")).find("--solution"), std::string::npos);
}

TEST(SceneLoaderMalformed, FarAwayCameraOrVerticesAreRefused) {
  test::TempDir dir("scene-loader");
  std::string error = test::loadErrorOf(dir.write(
      "far.json",
      sceneText(kLamp, R"({"type": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,1e30]], "material": "lamp"})")));
  EXPECT_NE(error.find("from the origin"), std::string::npos) << error;
}

}  // namespace
}  // namespace radiant
