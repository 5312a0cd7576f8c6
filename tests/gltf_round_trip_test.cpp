// A file written by radiant export reads back as the same scene (issue 18):
// every material exactly (extras.radiant), each material's surface area to
// the float precision of the positions, the camera and the image's aspect.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "export/baked_mesh.h"
#include "export/gltf_writer.h"
#include "identity_display.h"
#include "path_image_comparison.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"
#include "refined_mesh.h"
#include "scene/load_scene.h"

namespace radiant {
namespace {

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
    const BakedMesh baked = bakeSolution(scene, solution, test::identityDisplay);
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

// The image of the exported refined mesh (T-vertices, fans, float positions),
// path-traced, is the original scene's: it loads with no warning (no
// degenerate or overlapping faces) and, in each of 16 blocks of the image,
// the two independent renders' means differ by less than 4.5 standard errors
// (their variances from the films; 4.5σ over 16 blocks fails a right
// scene about once in 10⁴ runs), and over the whole image by less than 4.
TEST(GltfRoundTrip, TheExportsPathTracedImageIsTheOriginals) {
  const Scene scene = loadScene(RADIANT_SOURCE_DIR "/scenes/cornell-box/scene.json");
  RadiosityMesh mesh = test::refinedTreeMesh(scene, 0.15);
  ASSERT_FALSE(mesh.tVertices.empty());
  Solution solution = initialSolution(scene, std::move(mesh));
  const std::string path = (std::filesystem::temp_directory_path() / "radiant-round-trip-path.glb").string();
  writeGltf(scene, bakeSolution(scene, solution, test::identityDisplay), ExportProvenance{"none", "linear", {}, ""},
            path);
  const Scene back = loadScene(path);
  std::filesystem::remove(path);
  EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
  EXPECT_EQ(back.droppedDegenerateFaces, 0u);

  const int size = 32, spp = 512;
  const Film original = test::pathTraced(scene, scene.camera, size, spp, 1);
  const Film exported = test::pathTraced(back, scene.camera, size, spp, 2);
  // The whole image (σ ≈ 0.6 %: 3 % more light fails at 5σ), then each block (a wrong part of the scene).
  const test::RegionSums all = test::regionSums(original, exported, 0, 0, size, size);
  EXPECT_LT(std::abs(all.a - all.b), 4 * std::sqrt(all.variance)) << "image sums " << all.a << " vs " << all.b;
  const int block = size / 4;
  for (int by = 0; by < size; by += block)
    for (int bx = 0; bx < size; bx += block) {
      const test::RegionSums r = test::regionSums(original, exported, bx, by, block, block);
      EXPECT_LT(std::abs(r.a - r.b), 4.5 * std::sqrt(r.variance) + 1e-12)
          << "block " << bx / block << "," << by / block << ": " << r.a << " vs " << r.b;
    }
}

}  // namespace
}  // namespace radiant
