// A file written by radiant export reads back as the same scene (issue 18):
// every material exactly (extras.radiant), each material's surface area to
// the float precision of the positions, the camera and the image's aspect.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "export/baked_mesh.h"
#include "export/gltf_writer.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "scene/load_scene.h"

namespace radiant {
namespace {

void identityDisplay(const float radiance[3], double display[3]) {
  for (int c = 0; c < 3; ++c) display[c] = std::clamp(double(radiance[c]), 0.0, 1.0);
}

std::map<std::string, double> areaByMaterial(const Scene &scene) {
  std::map<std::string, double> area;
  for (const Face &f : scene.faces) area[scene.materials[f.material].name] += scene.faceArea(f);
  return area;
}

TEST(GltfRoundTrip, AnExportedSceneReadsBackAsTheSameScene) {
  for (const char *name : {"cornell-box", "cornell-specular"}) {
    SCOPED_TRACE(name);
    const Scene scene = loadScene(std::string(RADIANT_SOURCE_DIR "/scenes/") + name + "/scene.json");
    RayTracer tracer(scene);
    MeshOptions meshOptions;
    meshOptions.maxEdgeLength = 0.2;
    Solution solution = initialSolution(scene, buildMesh(scene, meshOptions));
    SolverOptions options;
    options.solver = "gauss-seidel";
    options.tolerance = 1e-2;
    solveRadiosity(tracer, solution, options);
    const BakedMesh baked = bakeSolution(scene, solution, identityDisplay);
    for (const std::string extension : {".glb", ".gltf"}) {
      SCOPED_TRACE(extension);
      const std::string path =
          (std::filesystem::temp_directory_path() / ("radiant-gltf-round-trip-" + std::string(name) + extension))
              .string();
      writeGltf(scene, baked, ExportProvenance{"gauss-seidel", "linear", {{"exposure", 0.0}}, "linear"}, path);
      const Scene back = loadScene(path);
      std::filesystem::remove(path);

      const std::map<std::string, double> before = areaByMaterial(scene), after = areaByMaterial(back);
      ASSERT_EQ(before.size(), after.size());
      for (const auto &[material, area] : before) {
        ASSERT_TRUE(after.count(material)) << material;
        EXPECT_NEAR(after.at(material), area, 1e-6 * area) << material;
      }
      for (const Material &m : back.materials) {
        SCOPED_TRACE(m.name);
        const Material *original = nullptr;
        for (const Material &o : scene.materials)
          if (o.name == m.name) original = &o;
        ASSERT_NE(original, nullptr);
        EXPECT_EQ(m.kind, original->kind);
        for (int c = 0; c < kBandCount; ++c) {
          EXPECT_EQ(m.diffuse[c], original->diffuse[c]);
          EXPECT_EQ(m.specular[c], original->specular[c]);
          EXPECT_EQ(m.emission[c], original->emission[c]);
        }
        EXPECT_EQ(m.ior, original->ior);
        EXPECT_EQ(m.roughness, original->roughness);
      }
      EXPECT_NEAR(length(back.camera.eye - scene.camera.eye), 0, 1e-9);
      EXPECT_GT(dot(normalize(back.camera.target - back.camera.eye), normalize(scene.camera.target - scene.camera.eye)),
                1 - 1e-12);
      EXPECT_GT(dot(back.camera.up, normalize(scene.camera.up)), 1 - 1e-9);
      EXPECT_NEAR(back.camera.verticalFovDegrees, scene.camera.verticalFovDegrees, 1e-9);
      EXPECT_EQ(back.render.width * scene.render.height, back.render.height * scene.render.width);
    }
  }
}

}  // namespace
}  // namespace radiant
